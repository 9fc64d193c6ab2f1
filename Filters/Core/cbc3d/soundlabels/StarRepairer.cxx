#include "cbc3d/soundlabels/StarRepairer.h"

#include "cbc3d/soundlabels/ImageRegions.h"

#include <algorithm>
#include <limits>
#include <queue>

namespace cbc3d
{
namespace
{
constexpr std::int64_t Unreachable = std::numeric_limits<std::int64_t>::max();
// Each step of a joining path costs a little, so that of equal paths the shorter wins.
constexpr std::int64_t StepCost = 1;
// Repairs in one visit, and visits, before a vertex's whole star takes one class (by votes,
// then, after more visits, by rank).
constexpr int RoundsPerVisit = 10;
constexpr int VisitsBeforeFallback = 3;
constexpr int VisitsBeforeRankedFallback = 6;
// How far (in tets) to look for a join of two parts elsewhere before joining them here. The
// background has more tets near a vertex (the lattice keeps a ring of them round the tissues),
// so its search visits more for the same reach.
constexpr std::size_t JoinSearchTets = 2000;
constexpr std::size_t BackgroundJoinSearchTets = 3000;
} // namespace

// The cheapest path of `through` nodes from the `from` nodes to a node linked to a `goal` node,
// each step costing the node's relabelling to `to`; fills `path` (without the ends).
std::int64_t StarRepairer::Path(const VertexStar& star, const std::vector<int>& from,
  const std::vector<char>& through, const std::vector<char>& goal, std::int32_t to,
  std::vector<int>& path) const
{
  using Entry = std::pair<std::int64_t, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  std::vector<std::int64_t> best(star.Nodes(), Unreachable);
  std::vector<int> previous(star.Nodes(), -1);
  for (const int node : from)
  {
    best[node] = 0;
    open.emplace(0, node);
  }
  while (!open.empty())
  {
    const auto [cost, node] = open.top();
    open.pop();
    if (cost > best[node])
    {
      continue;
    }
    if (goal[node])
    {
      path.clear();
      for (int at = previous[node]; at >= 0 && best[at] > 0; at = previous[at])
      {
        path.push_back(at);
      }
      return cost;
    }
    for (const int next : star.Links[node])
    {
      const bool step = through[next] && this->Changeable(star, next);
      if (!step && !goal[next])
      {
        continue;
      }
      const std::int64_t added = goal[next] ? 0 : std::max<std::int64_t>(0, this->Cost(star, next, to)) + StepCost;
      if (cost + added < best[next])
      {
        best[next] = cost + added;
        previous[next] = node;
        open.emplace(best[next], next);
      }
    }
  }
  return Unreachable;
}

void StarRepairer::Relabel(VertexStar& star, int node, std::int32_t to, std::vector<std::int64_t>& changed)
{
  if (!this->Changeable(star, node))
  {
    return; // the outside stays background
  }
  star.Class[node] = to;
  this->Classes[star.Tets[node]] = to;
  changed.push_back(star.Tets[node]);
}

// Whether the class's tets join the spare part to the keeper through faces within a short walk
// (a bounded breadth-first search from the spare part's tets).
bool StarRepairer::JoinedNearby(const VertexStar& star, const std::vector<int>& part, int keeper, int spare,
  std::int32_t cls)
{
  constexpr int Visited = -2, Goal = -3;
  std::vector<std::int64_t>& queue = this->SearchQueue; // kept: tens of thousands of searches
  queue.clear();
  for (int node = 0; node < static_cast<int>(star.Tets.size()); ++node)
  {
    if (part[node] == spare)
      queue.push_back(star.Tets[node]);
    else if (part[node] == keeper)
      this->LocalOf[star.Tets[node]] = Goal;
  }
  for (const std::int64_t t : queue)
    this->LocalOf[t] = Visited;
  bool joined = false;
  const std::size_t bound = cls == this->Background ? BackgroundJoinSearchTets : JoinSearchTets;
  for (std::size_t next = 0; next < queue.size() && next < bound && !joined; ++next)
  {
    for (const std::int64_t n : this->Across[queue[next]])
    {
      if (n < 0 || this->Classes[n] != cls || this->LocalOf[n] == Visited)
        continue;
      if (this->LocalOf[n] == Goal)
      {
        joined = true;
        break;
      }
      this->LocalOf[n] = Visited;
      queue.push_back(n);
    }
  }
  for (const std::int64_t t : queue)
    this->LocalOf[t] = -1;
  for (int node = 0; node < static_cast<int>(star.Tets.size()); ++node)
    this->LocalOf[star.Tets[node]] = -1;
  return joined;
}

// The parts (`part`: of class `to` around the vertex) next to the tets that `giveAway` gives to
// `to`, sorted.
std::vector<int> StarRepairer::TouchedParts(const VertexStar& star, const std::vector<int>& part, std::int32_t to,
  const std::vector<std::pair<int, std::int32_t>>& giveAway) const
{
  std::vector<int> touched;
  for (const auto& [node, cls] : giveAway)
  {
    if (cls != to)
      continue;
    for (const int next : star.Links[node])
      if (part[next] >= 0)
        touched.push_back(part[next]);
  }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  return touched;
}

// Whether giving tets away (each node to its class in `giveAway`, one of `receivers`) would
// join two parts of a receiving class around the vertex that the class already joins nearby:
// close a loop in it.
bool StarRepairer::GivingJoinsNearby(const VertexStar& star, const std::vector<std::int32_t>& receivers,
  const std::vector<std::pair<int, std::int32_t>>& giveAway)
{
  for (const std::int32_t to : receivers)
  {
    std::vector<int> part;
    if (StarComponents(star, [&](int node) { return star.Class[node] == to; }, part) < 2)
      continue;
    const std::vector<int> touched = this->TouchedParts(star, part, to, giveAway);
    for (std::size_t i = 1; i < touched.size(); ++i)
      if (this->JoinedNearby(star, part, touched[0], touched[i], to))
        return true;
  }
  return false;
}

// The image's background components (kept cavities, or the outside) that the tets of one part
// stand for, sorted: none where the image has no cavity to keep.
std::vector<std::int32_t> StarRepairer::RegionsOfPart(const VertexStar& star, const std::vector<int>& part, int which) const
{
  std::vector<std::int32_t> regions;
  if (this->RegionOfTet.empty())
    return regions;
  for (int node = 0; node < static_cast<int>(star.Tets.size()); ++node)
    if (part[node] == which && this->RegionOfTet[star.Tets[node]] != NoRegion)
      regions.push_back(this->RegionOfTet[star.Tets[node]]);
  std::sort(regions.begin(), regions.end());
  regions.erase(std::unique(regions.begin(), regions.end()), regions.end());
  return regions;
}

// Whether two parts of the background stand for components the image keeps apart: each stands
// for some, and they share none.
bool StarRepairer::KeptApart(const VertexStar& star, const std::vector<int>& part, int a, int b) const
{
  const std::vector<std::int32_t> first = this->RegionsOfPart(star, part, a);
  const std::vector<std::int32_t> second = this->RegionsOfPart(star, part, b);
  if (first.empty() || second.empty())
    return false;
  return std::none_of(first.begin(), first.end(),
    [&](std::int32_t r) { return std::binary_search(second.begin(), second.end(), r); });
}

// Whether giving tets to the background would join two of its parts around the vertex that the
// image keeps apart: open a cavity of the image (a hole in the wall round it).
bool StarRepairer::GivingOpensCavity(const VertexStar& star, const std::vector<std::pair<int, std::int32_t>>& giveAway) const
{
  if (this->RegionOfTet.empty())
    return false;
  std::vector<int> part;
  if (StarComponents(star, [&](int node) { return star.Class[node] == this->Background; }, part) < 2)
    return false;
  const std::vector<int> touched = this->TouchedParts(star, part, this->Background, giveAway);
  for (std::size_t i = 0; i < touched.size(); ++i)
    for (std::size_t j = i + 1; j < touched.size(); ++j)
      if (this->KeptApart(star, part, touched[i], touched[j]))
        return true;
  return false;
}

// Giving the spare part of a class away: each of its tets to the neighbouring class (one of
// `alternatives`) it holds most of. Returns the votes that costs (Unreachable: no neighbour).
std::int64_t StarRepairer::PlanGiveAway(const VertexStar& star, const std::vector<int>& part, int spare, std::int32_t cls,
  std::vector<std::int32_t>& alternatives, std::vector<std::pair<int, std::int32_t>>& giveAway) const
{
  for (int node = 0; node < star.Nodes(); ++node)
    if (part[node] == spare)
      for (const int next : star.Links[node])
        if (star.Class[next] != cls)
          alternatives.push_back(star.Class[next]);
  std::sort(alternatives.begin(), alternatives.end());
  alternatives.erase(std::unique(alternatives.begin(), alternatives.end()), alternatives.end());
  if (alternatives.empty())
    return Unreachable;
  std::int64_t cost = 0;
  for (int node = 0; node < star.Nodes(); ++node)
  {
    if (part[node] != spare)
      continue;
    std::int32_t to = alternatives.front();
    for (const std::int32_t other : alternatives)
      if (this->VotesOf(star, node, other) > this->VotesOf(star, node, to))
        to = other;
    giveAway.emplace_back(node, to);
    cost += this->Cost(star, node, to);
  }
  return cost;
}

// A class in several parts around the vertex: the part it can best spare is either joined to
// the part it values most, or given to its neighbours, whichever costs fewer votes.
void StarRepairer::RepairSplit(VertexStar& star, std::int32_t cls, std::vector<std::int64_t>& changed)
{
  std::vector<int> part;
  const int parts = StarComponents(star, [&](int node) { return star.Class[node] == cls; }, part);
  std::vector<std::int64_t> worth(parts, 0);
  for (int node = 0; node < star.Nodes(); ++node)
    if (part[node] >= 0)
      worth[part[node]] += this->VotesOf(star, node, cls);
  const int keeper = int(std::max_element(worth.begin(), worth.end()) - worth.begin());
  int spare = keeper == 0 ? 1 : 0;
  for (int p = 0; p < parts; ++p)
    if (p != keeper && worth[p] < worth[spare])
      spare = p;

  std::vector<std::int32_t> alternatives;
  std::vector<std::pair<int, std::int32_t>> giveAway;
  const std::int64_t giveCost = this->PlanGiveAway(star, part, spare, cls, alternatives, giveAway);

  // Joining it: the cheapest path of other tets from the keeper to the spare part.
  std::vector<int> from, path;
  std::vector<char> through(star.Nodes(), 0), goal(star.Nodes(), 0);
  for (int node = 0; node < star.Nodes(); ++node)
  {
    if (part[node] == keeper)
      from.push_back(node);
    goal[node] = part[node] == spare;
    through[node] = part[node] < 0;
  }
  // Parts that the class already joins elsewhere would close a loop here: a handle. The
  // background's loop is taken all the same where giving its part away would close one in a
  // tissue instead: a loop of the background around a tissue that is joined elsewhere is no
  // handle of the tissue, a second join of the tissue is (the ventricles' surface gets the
  // image's Euler characteristic this way, -2 instead of -4). Neither may open a cavity of the
  // image: background parts that stand for a cavity and for the outside (or for two cavities)
  // stay apart whatever it costs, so a thin wall round a cavity is thickened, not punched.
  const std::int64_t joinCost = this->Path(star, from, through, goal, cls, path);
  const bool opensCavity = cls == this->Background ? this->KeptApart(star, part, keeper, spare)
                                                   : this->GivingOpensCavity(star, giveAway);
  // (The searches for a loop, a few thousand tets each, only where they can change the answer.)
  const auto closesLoop = [&] {
    return this->JoinedNearby(star, part, keeper, spare, cls) &&
      !(cls == this->Background && this->GivingJoinsNearby(star, alternatives, giveAway));
  };
  const bool join = opensCavity ? cls != this->Background && joinCost < Unreachable
                                : joinCost < giveCost && !closesLoop();
  if (join)
  {
    for (const int node : path)
      this->Relabel(star, node, cls, changed);
    return;
  }
  for (const auto& [node, to] : giveAway)
    this->Relabel(star, node, to, changed);
}

// A class ringing the vertex (its complement in several parts): the hole that is cheapest to
// fill takes the class. Where the class is the background, or where that hole holds a pinned
// tet or the outside, the ring may instead be cut by a path of the hole's class (two tissues
// that touched only here then share a face; a kept component's last tet stays).
void StarRepairer::RepairRing(VertexStar& star, std::int32_t cls, std::vector<std::int64_t>& changed)
{
  std::vector<int> hole;
  const int holes = StarComponents(star, [&](int node) { return star.Class[node] != cls; }, hole);
  std::vector<std::int64_t> fillCost(holes, 0);
  for (int node = 0; node < star.Nodes(); ++node)
    if (hole[node] >= 0)
      fillCost[hole[node]] += this->Cost(star, node, cls);
  const int keeper = int(std::max_element(fillCost.begin(), fillCost.end()) - fillCost.begin());
  int fill = keeper == 0 ? 1 : 0;
  for (int h = 0; h < holes; ++h)
    if (h != keeper && fillCost[h] < fillCost[fill])
      fill = h;

  // Filling the cheapest hole would take a pinned tet or the outside: cut the ring instead.
  if (cls == this->Background || fillCost[fill] >= PinnedVotes)
  {
    // The class the hole holds most of, for the cutting path.
    std::int32_t to = cls;
    std::int64_t most = -1;
    for (int node = 0; node < star.Nodes(); ++node)
      if (hole[node] == fill && this->VotesOf(star, node, star.Class[node]) > most)
      {
        most = this->VotesOf(star, node, star.Class[node]);
        to = star.Class[node];
      }
    std::vector<int> from, path;
    std::vector<char> through(star.Nodes(), 0), goal(star.Nodes(), 0);
    for (int node = 0; node < star.Nodes(); ++node)
    {
      if (hole[node] == fill)
        from.push_back(node);
      goal[node] = hole[node] >= 0 && hole[node] != fill;
      through[node] = hole[node] < 0;
    }
    const std::int64_t cutCost = this->Path(star, from, through, goal, to, path);
    if (cutCost < fillCost[fill])
    {
      for (const int node : path)
        this->Relabel(star, node, to, changed);
      return;
    }
  }
  for (int node = 0; node < star.Nodes(); ++node)
    if (hole[node] == fill)
      this->Relabel(star, node, cls, changed);
}

// The last resort: the whole star takes one class: the one with the most votes in it, or, once
// the vertex has had its share of those, the highest ranked (the tissue with the most tets).
// Tets only ever move up the ranks that way, so neighbouring vertices cannot undo each other's
// last resorts for ever. A pinned tet's class wins outright.
void StarRepairer::Unify(VertexStar& star, bool byRank, std::vector<std::int64_t>& changed)
{
  std::map<std::int32_t, std::int64_t> votes; // the star's votes for each class present
  for (const std::int32_t cls : star.Class)
    votes[cls] = 0;
  for (auto& [cls, sum] : votes)
    for (int node = 0; node < static_cast<int>(star.Tets.size()); ++node)
      sum += this->VotesOf(star, node, cls);
  std::int32_t best = this->Background;
  bool pinned = false;
  for (int node = 0; node < star.Nodes() && !pinned; ++node)
  {
    const std::int32_t cls = star.Class[node];
    pinned = star.IsTet(node) && this->VotesOf(star, node, cls) >= PinnedVotes;
    const bool better = byRank ? this->Rank(cls) > this->Rank(best) : votes[cls] > votes[best];
    if (pinned || better)
      best = cls;
  }
  for (int node = 0; node < star.Nodes(); ++node)
    if (star.IsTet(node) && star.Class[node] != best)
      this->Relabel(star, node, best, changed);
  StarViolation violation;
  if (this->FindViolation(star, violation))
  {
    // The mesh boundary itself pinches here: leave the vertex to the background, for good.
    for (int node = 0; node < star.Nodes(); ++node)
      if (star.IsTet(node) && star.Class[node] != this->Background)
        this->Relabel(star, node, this->Background, changed);
    if (this->Frozen.empty())
      this->Frozen.assign(this->TetList.size(), 0);
    for (const std::int64_t t : star.Tets)
      this->Frozen[t] = 1;
  }
}

void StarRepairer::RepairStar(PointId v, int visit, std::vector<std::int64_t>& changed,
  ManifoldRepairResult& result)
{
  VertexStar& star = this->Scratch;
  this->Load(v, star);
  StarViolation violation;
  if (!this->FindViolation(star, violation))
  {
    return;
  }
  ++result.Repairs;
  for (int round = 0; visit < VisitsBeforeFallback && round < RoundsPerVisit; ++round)
  {
    if (violation.Split)
      this->RepairSplit(star, violation.Class, changed);
    else
      this->RepairRing(star, violation.Class, changed);
    if (!this->FindViolation(star, violation))
    {
      return;
    }
  }
  this->Unify(star, visit >= VisitsBeforeRankedFallback, changed);
}
} // namespace cbc3d
