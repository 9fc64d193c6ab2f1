/**
 * @file vtkCBC3DBandTets.h
 * @brief The tets near the cuts between MPI ranks' slabs, shared, and the meshes that the
 *        deformation runs on built from them (private to vtkCBC3DRankDeformation).
 *
 * Each rank sends the tets it owns within three lattice cubes of a cut to the ranks on either side
 * of that cut, and to no other: each corner once (global id, undeformed key along the cut axis,
 * current place), and each tet as four corners and a label. A rank then builds the mesh of one
 * run from its own tets and those its neighbours sent, on global ids.
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

/// The tets other ranks sent to this one, sender by sender in rank order. Each sender's part of
/// `Numbers` is: its point count, its tet count, the points' global ids, their axis keys, the
/// tets' corners (four indices into its points each) and the tets' labels; its part of `Places`
/// is the points' places, three values each.
struct BandTets
{
  BandTets();
  ~BandTets();
  vtkSmartPointer<vtkTypeInt64Array> Numbers;
  vtkSmartPointer<vtkDoubleArray> Places;
};

/// Sends this rank's tets (of `owned`, with GlobalIds; `axisKeys` per point) that have a corner
/// within ReachCubes of a cut to the two ranks beside that cut, and receives those sent to it.
/// `cutKeys[c]` is the cut between ranks c and c + 1. A collective call.
void Share(vtkMultiProcessController* controller, vtkUnstructuredGrid* owned, const std::vector<std::int64_t>& axisKeys,
  const std::vector<std::int64_t>& cutKeys, std::int64_t cubeKeys, BandTets& received);

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
  /// The tets other ranks sent with a corner whose key satisfies `keep`, sender by sender;
  /// returns their volume by label.
  std::map<vtkTypeInt64, double> AddOthers(const BandTets& received, const std::function<bool(std::int64_t)>& keep);

  vtkIdType Place(vtkIdType id) const { return this->Local.at(id); }
  const std::unordered_map<vtkIdType, vtkIdType>& Places() const { return this->Local; }
  std::int64_t KeyAt(vtkIdType place) const { return this->Keys[place]; }
  /// Each tet's corners, as places.
  const std::vector<std::array<vtkIdType, 4>>& Tets() const { return this->Corners; }

  /// The mesh, with the points at `free` (places) free and the rest fixed. Takes the tets:
  /// Tets() is empty after.
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
