#ifndef cbc3d_ManifoldRepair_h
#define cbc3d_ManifoldRepair_h

#include "cbc3d/base/TetMesh.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace cbc3d
{
/// How much tet `tet` wants class `cls`: its voxel weight of that class. Relabelling a tet from
/// a to b costs Votes(tet, a) - Votes(tet, b).
using ClassVotes = std::function<std::int64_t(std::int64_t tet, std::int32_t cls)>;

/// Votes of at least this much pin a tet to its class: even the last resort keeps it.
constexpr std::int64_t PinnedVotes = std::int64_t(1) << 48;

struct ManifoldRepairResult
{
  std::int64_t Relabelled = 0; // tet relabellings (a tet may count more than once)
  std::int64_t Repairs = 0;    // vertex stars repaired
  std::int64_t Unrepaired = 0; // vertices still not manifold (0 unless the work bound was hit)
};

/// Makes every class's region manifold at every vertex by relabelling tets: around each vertex
/// the tets of a class must form one face-connected fan, and so must the tets of every other
/// class together, so the class's boundary there is one disk. Beyond the mesh counts as class
/// `background` (the mesh may have gaps and pinches of its own: each gap at a vertex is told
/// apart by the order of its faces round their edges, from the `points`). This forbids tets that share only an edge or a vertex with the rest of their
/// class (hinges), and non-manifold edges and vertices on every boundary and interface.
///
/// A class split into parts around a vertex is either joined (the cheapest face-connected path
/// of other tets between the parts takes the class) or loses its smaller part (to the best
/// neighbouring class), whichever changes fewer voxel votes; a class ringing a vertex is
/// thickened into the smaller hole of the ring. A vertex that keeps failing gets its whole star
/// in the class with the most votes there. Where `backgroundRegionOfTet` (BackgroundRegionOfTets)
/// is given, no repair joins two parts of the background that stand for components the image
/// keeps apart (a cavity and the outside, or two cavities): a thin wall round a cavity is
/// thickened rather than punched. Only vertices next to a change are looked at again,
/// so the work follows the defects, not the mesh. `seeds`, when not empty, are the only
/// vertices examined at first; without them, every vertex is first checked in parallel on
/// `numberOfThreads` threads (0 = all cores). Deterministic: the same for any thread count.
ManifoldRepairResult RepairManifoldLabels(const std::vector<Eigen::Vector3d>& points,
  const std::vector<Tet>& tets, const std::vector<TetNeighbours>& across,
  std::int32_t background, const ClassVotes& votes, std::vector<std::int32_t>& classes,
  const std::vector<PointId>& seeds = {}, int numberOfThreads = 1,
  const std::vector<std::int32_t>& backgroundRegionOfTet = {});

/// The vertices where some class is not manifold (the condition RepairManifoldLabels makes).
std::int64_t CountNonManifoldVertices(const std::vector<Eigen::Vector3d>& points,
  const std::vector<Tet>& tets, const std::vector<TetNeighbours>& across,
  std::int32_t background, const std::vector<std::int32_t>& classes);
} // namespace cbc3d

#endif
