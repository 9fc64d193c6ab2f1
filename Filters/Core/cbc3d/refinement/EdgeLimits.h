#ifndef cbc3d_EdgeLimits_h
#define cbc3d_EdgeLimits_h

#include "cbc3d/refinement/LabelledMesh.h"

#include <cstddef>
#include <vector>

namespace cbc3d
{
/// The mark of a leaf split for an edge limit (other marks are 1): such splits obey only the
/// user's minimum edge length, not the automatic one (the voxel size).
constexpr char MarkedForEdgeLimit = 2;

/// Marks (in `marked`, per red tet of `hierarchy`) the red leaves whose longest edge is longer
/// than a tissue's edge limit (RefinementParams::MaximumEdge) allows: the leaves of tets
/// labelled with the tissue, and of tets holding any voxel of it, so that tets that making the
/// labels sound may give to the tissue are refined too. A red split halves every edge, and the
/// green tets of a leaf have no edge longer than the leaf's, so marked leaves end within the
/// limits after enough passes. Returns the number of leaves it marked.
std::size_t MarkForMaximumEdge(const LabelImage& image, const RefinementParams& params,
  const RedGreenMesh& hierarchy, const LabelledMesh& mesh, std::vector<char>& marked);

/// An error where an edge limit lies below the minimum edge length the user gave (it could
/// never be met); the automatic floor, the voxel size, gives way to edge limits.
Status CheckEdgeLimitsAboveFloor(const RefinementParams& params);

/// Red-splits the leaves of the tissue tets of `mesh` (after the sound labels) whose edges pass
/// their tissue's limit, where the user's minimum edge length allows; returns whether it split
/// any.
bool SplitOverlongTets(const LabelImage& image, const RefinementParams& params, RedGreenMesh& hierarchy,
  const LabelledMesh& mesh);

/// The tets (of `tets`, with `labels`) with an edge longer than their tissue's limit allows,
/// after refinement and the sound labels.
std::size_t CountOverlongEdges(const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets,
  const std::vector<std::int32_t>& labels, const LabelImage& image, const RefinementParams& params);
} // namespace cbc3d

#endif
