/**
 * @file vtkCBC3DBandTets.h
 * @brief The tets near the cuts between MPI ranks' slabs, shared, and the meshes that the
 *        deformation runs on built from them (private to vtkCBC3DRankDeformation).
 *
 * Each rank sends the tets it owns within two lattice cubes of a cut: their corners' global ids,
 * undeformed keys along the cut axis and current places, and their labels. A rank then builds
 * the mesh of one run from its own tets and those of its neighbours, on global ids.
 */
#ifndef vtkCBC3DBandTets_h
#define vtkCBC3DBandTets_h

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <unordered_map>
#include <vector>

class vtkCellArray;
class vtkDataArray;
class vtkDoubleArray;
class vtkMultiProcessController;
class vtkPoints;
class vtkTypeInt64Array;
class vtkUnstructuredGrid;

namespace vtkCBC3DBandTets
{
/// How far from a cut the second phase moves points (lattice cubes), and how far the tets it
/// runs on reach: a cube more, the largest tet's extent, so that every moved point has all its
/// tets and the voxels it answers for are all inside tets.
constexpr int BandCubes = 2;
constexpr int ReachCubes = BandCubes + 1;

/// Every rank's tets near its cuts: rows of (rank, four global ids, label, four axis keys) and
/// the corners' places (twelve values a row).
struct BandTets
{
  BandTets();
  ~BandTets();
  vtkSmartPointer<vtkTypeInt64Array> Rows;
  vtkSmartPointer<vtkDoubleArray> Places;
  static constexpr int RowSize = 10;
  vtkIdType Count() const;
  const vtkTypeInt64* Row(vtkIdType r) const;
  const double* PlacesOf(vtkIdType r) const;
};

/// Sends this rank's tets (of `owned`, with GlobalIds; `axisKeys` per point) that have a corner
/// within ReachCubes of a cut, and gathers every rank's. A collective call.
void Share(vtkMultiProcessController* controller, vtkUnstructuredGrid* owned, const std::vector<std::int64_t>& axisKeys,
  const std::vector<std::int64_t>& cutKeys, std::int64_t cubeKeys, BandTets& all);

/// A mesh for one run of the deformation filter, made tet by tet on global ids: each point once,
/// with its axis key; fixed unless freed.
class RunMesh
{
public:
  explicit RunMesh(vtkDataArray* labelType);
  ~RunMesh();

  /// Adds a tet from its corners' global ids, axis keys and places (twelve values); returns its
  /// volume.
  double Add(const vtkTypeInt64 ids[4], const vtkTypeInt64 keys[4], const double* places, double label);
  /// The tets of `owned` whose corners' keys satisfy `keep` (any corner), in their order.
  void AddOwned(vtkUnstructuredGrid* owned, const std::vector<std::int64_t>& axisKeys,
    const std::function<bool(std::int64_t)>& keep);
  /// The other ranks' rows (not `me`'s) with a corner whose key satisfies `keep`; returns their
  /// volume by label.
  std::map<vtkTypeInt64, double> AddOthers(const BandTets& all, int me, const std::function<bool(std::int64_t)>& keep);

  vtkIdType Place(vtkIdType id) const { return this->Local.at(id); }
  const std::unordered_map<vtkIdType, vtkIdType>& Places() const { return this->Local; }
  std::int64_t KeyAt(vtkIdType place) const { return this->Keys[place]; }
  /// Each tet's corners, as places.
  const std::vector<std::array<vtkIdType, 4>>& Tets() const { return this->Corners; }

  /// The mesh, with the points at `free` (places) free and the rest fixed.
  vtkSmartPointer<vtkUnstructuredGrid> Make(const std::vector<vtkIdType>& free);

private:
  vtkIdType AddPoint(vtkIdType id, std::int64_t key, const double x[3]);

  vtkSmartPointer<vtkPoints> Points;
  vtkSmartPointer<vtkDataArray> Labels;
  std::vector<std::array<vtkIdType, 4>> Corners;
  std::vector<std::int64_t> Keys;
  std::unordered_map<vtkIdType, vtkIdType> Local;
};
} // namespace vtkCBC3DBandTets

#endif
