#ifndef cbc3d_TetMesh_h
#define cbc3d_TetMesh_h

// Stage: the shared base, below every other stage. The tet mesh (points, tets, labels) with its
// geometry, topology tables, faces and tagged faces; the label image and its codes; the point
// grid for nearest-point searches; status, progress and the parallel helpers. It includes no
// other stage.

#include "cbc3d/base/Status.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace cbc3d
{
using PointId = std::int64_t;
using Tet = std::array<PointId, 4>;

/// A labelled tetrahedral mesh in world coordinates (structure of arrays).
/// Tets follow VTK_TETRA's vertex order and are positively oriented (see TetTopology.h).
struct TetMesh
{
  std::vector<Eigen::Vector3d> Points;
  std::vector<Tet> Tets;
  std::vector<std::int32_t> Labels; // one tissue label per tet
};

/// The longest edge of `tet` with its points at `points`.
double LongestEdgeOf(const std::vector<Eigen::Vector3d>& points, const Tet& tet);

/// Checks that labels match tets, indices are in range, and every tet has positive volume.
Status ValidateTetMesh(const TetMesh& mesh);
} // namespace cbc3d

#endif
