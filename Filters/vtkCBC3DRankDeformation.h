/**
 * @file vtkCBC3DRankDeformation.h
 * @brief Deformation over MPI ranks: each point moves once, by one rank, seeing every tet
 *        around it (private to vtkCBC3DMesher).
 *
 * Two phases, each a run of the deformation filter:
 * 1. Every rank deforms its own tets against its slab's voxels, with the seam points (those its
 *    neighbours' tets use too) held. Every point that moves has all its tets on that rank, so the
 *    angle and fidelity guards see them all.
 * 2. The ranks swap the tets around the seam points, moved. The lower rank at each cut then
 *    deforms its seam points alone, against the voxels near the cut, with every tet around them
 *    in hand and every other point held; it sends their places to the ranks that share them. A
 *    seam point that shares a tet with a seam point another rank moves stays where it is.
 * In the first phase a rank also holds its neighbours' tets around the seam points, fixed, and
 * sees a few slices past each cut, so that its guards see the voxels and vertices beyond. The
 * tissues' volumes are kept in that phase: each rank aims at its slab's voxels, offset by the
 * tissue its tets hold beyond the slab less what its neighbours' tets hold inside it, plus the
 * neighbours' tets it holds, less the voxels past the cuts it sees.
 *
 * `imageLabels` is the piece image's label array.
 */
#ifndef vtkCBC3DRankDeformation_h
#define vtkCBC3DRankDeformation_h

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkMultiProcessController;
class vtkPoints;
class vtkUnstructuredGrid;

namespace vtkCBC3DRankDeformation
{
/// How the image is cut into slabs, in voxel slices and in lattice keys.
struct Layout
{
  int Axis = 2;
  std::vector<int> Cuts;              // slab r: slices [Cuts[r], Cuts[r + 1])
  std::vector<std::int64_t> CutKeys;  // the plane before slab r + 1, in keys
  std::int64_t CubeKeys = 256;        // a lattice cube's edge, in keys
  double Cube = 0.0;                  // the same in mm
};

/// Runs the deformation filter on `mesh` against `image` and gives the moved points; returns
/// the filter's error, empty when it ran.
using RunDeformation = std::function<std::string(vtkUnstructuredGrid* mesh, vtkImageData* image, vtkPoints* moved)>;

/**
 * Deforms this rank's own tets (`owned`: GlobalIds and LatticeKey points, Label cells) in place,
 * with `image` its piece of the label image. A collective call: every rank makes it, one
 * without tets too. False on every rank where some rank's run failed, its error in `error`.
 */
bool DeformAcrossRanks(vtkMultiProcessController* controller, const Layout& layout, vtkImageData* image,
  vtkDataArray* imageLabels, vtkUnstructuredGrid* owned, const RunDeformation& run, std::string& error);
} // namespace vtkCBC3DRankDeformation

#endif
