/**
 * @file vtkCBC3DSeamPoints.h
 * @brief The points that MPI ranks' pieces share, and how much tissue a mesh holds beyond a
 *        slab (private: vtkCBC3DRankDeformation's inputs).
 *
 * A tet belongs to the rank whose slab holds its centre, so a point that tets of two ranks use
 * lies within a lattice cube of a cut. Each rank names its points that near a cut; a point two
 * ranks name is a seam point.
 */
#ifndef vtkCBC3DSeamPoints_h
#define vtkCBC3DSeamPoints_h

#include <vtkType.h>

#include <array>
#include <cstdint>
#include <map>
#include <unordered_set>
#include <vector>

class vtkMultiProcessController;
class vtkUnstructuredGrid;

namespace vtkCBC3DSeamPoints
{
/// The seam points of every rank's piece, by global id.
struct Seams
{
  std::unordered_set<vtkIdType> Points;

  bool IsSeam(vtkIdType id) const { return this->Points.count(id) != 0; }
};

/// The seams of the ranks' owned pieces (`mesh` with GlobalIds and LatticeKey points). `cutKeys`
/// are the keys of the planes between slabs along `axis`, `cubeKeys` a lattice cube edge in
/// keys. A collective call.
Seams FindSeams(vtkMultiProcessController* controller, vtkUnstructuredGrid* mesh, int axis,
  const std::vector<std::int64_t>& cutKeys, std::int64_t cubeKeys);

/// Per tissue label, the volume (mm^3) of this rank's tets beyond its slab less the volume of
/// its neighbours' tets inside it, on the undeformed tets (`mesh` with LatticeKey points, Label
/// cells): what the tissue of the rank's tets differs from its slab's by. Over all ranks these
/// sum to zero. A collective call.
std::map<vtkTypeInt64, double> TissueBeyondSlab(vtkMultiProcessController* controller, vtkUnstructuredGrid* mesh,
  int axis, const std::vector<std::int64_t>& cutKeys);

/// Per tissue label, the volume (mm^3) of the tets of `mesh` (Label cells).
std::map<vtkTypeInt64, double> TissueVolumes(vtkUnstructuredGrid* mesh);

/// Each point's key along `axis` (LatticeKey points: its undeformed place in 1/256 of a cube).
std::vector<std::int64_t> AxisKeys(vtkUnstructuredGrid* mesh, int axis);

} // namespace vtkCBC3DSeamPoints

#endif
