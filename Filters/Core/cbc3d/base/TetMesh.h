#ifndef cbc3d_TetMesh_h
#define cbc3d_TetMesh_h

// Stage: the shared base, below every other stage. The tet mesh (points, tets, labels) with its
// geometry, topology tables, faces and tagged faces; the label image and its codes; the point
// grid for nearest-point searches; status, progress and the parallel helpers. It includes no
// other stage.

#include "cbc3d/base/Status.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace cbc3d
{
// Point ids are 32 bits: tets are four of them, and 64-bit ids cost 16 bytes a tet in every copy
// of the tets a run holds. Where points are made, CheckPointCount keeps them within range.
using PointId = std::int32_t;
using Tet = std::array<PointId, 4>;
/// The tets across a tet's four faces, -1 where none (32-bit tet ids: CheckTetCount).
using TetNeighbours = std::array<std::int32_t, 4>;

/// A labelled tetrahedral mesh in world coordinates (structure of arrays).
/// Tets follow VTK_TETRA's vertex order and are positively oriented (see TetTopology.h).
struct TetMesh
{
  std::vector<Eigen::Vector3d> Points;
  std::vector<Tet> Tets;
  std::vector<std::int32_t> Labels; // one tissue label per tet
};

/// The most points a mesh may hold.
constexpr std::size_t MaxPoints = std::size_t(std::numeric_limits<PointId>::max());

/// Throws std::length_error when a mesh of `points` points would not fit 32-bit point ids.
void CheckPointCount(std::size_t points);

/// Throws std::length_error when a mesh of `tets` tets would not fit 32-bit tet ids (the tets
/// around a point, face neighbours, mesh faces).
void CheckTetCount(std::size_t tets);

/// The longest edge of `tet` with its points at `points`.
double LongestEdgeOf(const std::vector<Eigen::Vector3d>& points, const Tet& tet);

/// Checks that labels match tets, indices are in range, and every tet has positive volume.
Status ValidateTetMesh(const TetMesh& mesh);
} // namespace cbc3d

#endif
