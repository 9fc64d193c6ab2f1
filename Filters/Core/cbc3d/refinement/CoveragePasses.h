#ifndef cbc3d_CoveragePasses_h
#define cbc3d_CoveragePasses_h

// Refining for the boundary distance, pass by pass: where the surface would stay far from the
// image boundary, which tets to split (BoundaryCoverage.h measures the gaps).

#include "cbc3d/lattice/RedGreenMesh.h"
#include "cbc3d/refinement/BoundaryCoverage.h"
#include "cbc3d/refinement/LabelledMesh.h"
#include "cbc3d/refinement/RankPasses.h"
#include "cbc3d/refinement/Refinement.h"

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace cbc3d
{
/// How refining for the boundary distance stands between passes: the gaps the last pass found
/// (FarVoxels -1: none looked for yet), and whether a pass stopped gaining.
struct CoverageProgress
{
  double LargestGap = 0.0;
  std::int64_t FarVoxels = -1;
  bool Stalled = false; // the later passes refine for fidelity alone
};

/// Takes the gaps a pass found (over ranks, summed and maxed over the ranks: a collective call)
/// into `progress`; false, and progress stalled, where they are not narrower than the last.
bool CoverageGoesOn(BoundaryCoverage::Gaps& gaps, CoverageProgress& progress, const RankPasses* ranks);

/// Where the surface would stay far from the image boundary (more than `distance`): a new
/// surface vertex on the longest edge of the face nearest to a far boundary voxel (a green split
/// of the tets around the edge, into `bisect`), or a red split of the leaf where that edge is not
/// one of the leaf's own; and a red split of the tets with a vertex that cannot reach the
/// boundary. Returns whether any split was wanted (at the depth limit or not); none once a pass
/// brings neither the farthest voxel nearer nor fewer voxels far (`progress` then stalls).
bool MarkForCoverage(const LabelImage& image, const BoundaryCoverage& coverage, double distance, const RedGreenMesh& hierarchy,
  const LabelledMesh& mesh, double minimumEdge, CoverageProgress& progress, std::vector<char>& marked,
  std::vector<std::pair<PointId, PointId>>& bisect, const RankPasses* ranks);

/// The check of the boundary distance (0: 3/8 of the lattice's longest edge, recorded in
/// `result`); none where the bound is negative.
std::unique_ptr<BoundaryCoverage> MakeCoverage(const LabelImage& image, const TissueComponents& components,
  const RefinementParams& params, const RedGreenMesh& hierarchy, RefinementResult& result);
} // namespace cbc3d

#endif
