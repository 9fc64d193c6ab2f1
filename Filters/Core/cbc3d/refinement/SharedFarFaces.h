#ifndef cbc3d_SharedFarFaces_h
#define cbc3d_SharedFarFaces_h

#include "cbc3d/refinement/BoundaryCoverage.h"
#include "cbc3d/refinement/RankPasses.h"

#include <vector>

namespace cbc3d
{
/// Over ranks: the faces nearest to the far boundary voxels of every rank (`far`, this rank's),
/// over the whole mesh, that this rank's mesh holds, each once. Each rank offers the nearest of
/// the faces of its own tets (`owned`), and the nearest offer wins. A face near a slab's border
/// is in two ranks' pieces: both split it, so the pieces stay alike. Faces are told apart by
/// the positions of their points and of their tet's fourth point. A collective call; a rank
/// without tissue takes part with no coverage and no mesh.
std::vector<BoundaryCoverage::Face> FindFarFacesOnRanks(const RankPasses& ranks, const BoundaryCoverage* coverage,
  const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets, const std::vector<std::int32_t>& labels,
  const std::vector<std::pair<std::int32_t, Eigen::Vector3d>>& far, const std::vector<char>& owned);
} // namespace cbc3d

#endif
