#ifndef cbc3d_StarRepairer_h
#define cbc3d_StarRepairer_h

#include "cbc3d/soundlabels/ManifoldRepair.h"
#include "cbc3d/soundlabels/VertexStar.h"

#include <cstdint>
#include <map>
#include <vector>

namespace cbc3d
{
// The outside cannot change class: its votes outweigh any tet's (and a star's sum of them fits).
constexpr std::int64_t OutsideVotes = std::int64_t(1) << 52;

/// Repairs the labels round one vertex at a time (RepairManifoldLabels' worker): splits its
/// star's classes, rings and, as a last resort, gives the whole star one class.
class StarRepairer
{
public:
  StarRepairer(const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets,
    const std::vector<TetNeighbours>& across, std::int32_t background,
    const ClassVotes& votes, std::vector<std::int32_t>& classes,
    const std::vector<std::int32_t>& backgroundRegionOfTet = {}, int threads = 1)
    : TetList(tets)
    , Across(across)
    , Loader(points, tets, across, background, classes, threads)
    , Background(background)
    , Votes(votes)
    , Classes(classes)
    , RegionOfTet(backgroundRegionOfTet)
    , LocalOf(tets.size(), -1)
  {
    for (const std::int32_t cls : classes)
      ++this->TetsOfClass[cls];
  }

  void Load(PointId v, VertexStar& star) { this->Loader.Load(v, star, this->LocalOf); }
  /// The same with the caller's tet -> node scratch (all -1, and left so): for other threads.
  void Load(PointId v, VertexStar& star, std::vector<int>& localOf) const { this->Loader.Load(v, star, localOf); }
  bool FindViolation(const VertexStar& star, StarViolation& found) const
  {
    return FindStarViolation(star, this->Background, found);
  }
  bool IsUniform(PointId v) const { return this->Loader.IsUniform(v); }
  std::size_t TetCount() const { return this->TetList.size(); }
  void RepairStar(PointId v, int visit, std::vector<std::int64_t>& changed, ManifoldRepairResult& result);

private:
  std::int64_t VotesOf(const VertexStar& star, int node, std::int32_t cls) const
  {
    return star.IsTet(node) ? this->Votes(star.Tets[node], cls) : OutsideVotes;
  }
  // The outside, and the tets a last resort left to it, cannot change class.
  bool Changeable(const VertexStar& star, int node) const
  {
    return star.IsTet(node) && (this->Frozen.empty() || !this->Frozen[star.Tets[node]]);
  }
  std::int64_t Cost(const VertexStar& star, int node, std::int32_t to) const
  {
    if (!this->Changeable(star, node))
    {
      return to == star.Class[node] ? 0 : OutsideVotes;
    }
    return this->VotesOf(star, node, star.Class[node]) - this->VotesOf(star, node, to);
  }
  std::int64_t Path(const VertexStar& star, const std::vector<int>& from, const std::vector<char>& through,
    const std::vector<char>& goal, std::int32_t to, std::vector<int>& path) const;
  void Relabel(VertexStar& star, int node, std::int32_t to, std::vector<std::int64_t>& changed);
  bool JoinedNearby(const VertexStar& star, const std::vector<int>& part, int keeper, int spare, std::int32_t cls);
  bool GivingJoinsNearby(const VertexStar& star, const std::vector<std::int32_t>& receivers,
    const std::vector<std::pair<int, std::int32_t>>& giveAway);
  std::vector<int> TouchedParts(const VertexStar& star, const std::vector<int>& part, std::int32_t to,
    const std::vector<std::pair<int, std::int32_t>>& giveAway) const;
  std::vector<std::int32_t> RegionsOfPart(const VertexStar& star, const std::vector<int>& part, int which) const;
  bool KeptApart(const VertexStar& star, const std::vector<int>& part, int a, int b) const;
  bool GivingOpensCavity(const VertexStar& star, const std::vector<std::pair<int, std::int32_t>>& giveAway) const;
  std::int64_t PlanGiveAway(const VertexStar& star, const std::vector<int>& part, int spare, std::int32_t cls,
    std::vector<std::int32_t>& alternatives, std::vector<std::pair<int, std::int32_t>>& giveAway) const;
  void RepairSplit(VertexStar& star, std::int32_t cls, std::vector<std::int64_t>& changed);
  void RepairRing(VertexStar& star, std::int32_t cls, std::vector<std::int64_t>& changed);
  void Unify(VertexStar& star, bool byRank, std::vector<std::int64_t>& changed);

  const std::vector<Tet>& TetList;
  const std::vector<TetNeighbours>& Across;
  StarLoader Loader;
  std::int32_t Background;
  const ClassVotes& Votes;
  std::vector<std::int32_t>& Classes;
  const std::vector<std::int32_t>& RegionOfTet; // empty: the image has no cavity to keep
  std::vector<int> LocalOf; // scratch: tet -> its node in the star being loaded
  std::vector<std::int64_t> SearchQueue; // scratch of JoinedNearby
  VertexStar Scratch;             // the star being repaired
  std::map<std::int32_t, std::int64_t> TetsOfClass; // at the start: the last resort's ranks
  // Tets of stars where the mesh itself pinches, left to the background for good by the last
  // resort (empty until then): a neighbour taking them back would make the pinch again.
  std::vector<char> Frozen;

  std::int64_t Rank(std::int32_t cls) const
  {
    const auto found = this->TetsOfClass.find(cls);
    return cls == this->Background || found == this->TetsOfClass.end() ? -1 : found->second;
  }
};
} // namespace cbc3d

#endif
