#include "cbc3d/soundlabels/VertexStar.h"

#include "cbc3d/base/DisjointSets.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace cbc3d
{
namespace
{
// Numbers the parts of every class at once (nodes joined through links to nodes of their own
// class) into `found.Component`, and counts each class's parts into `found.Parts`.
void CountClassParts(const VertexStar& star, StarViolation& found)
{
  found.Component.assign(star.Nodes(), -1);
  found.Parts.clear();
  int count = 0;
  for (int seed = 0; seed < star.Nodes(); ++seed)
  {
    if (found.Component[seed] >= 0)
      continue;
    const std::int32_t cls = star.Class[seed];
    found.Component[seed] = count;
    found.Stack.assign(1, seed);
    while (!found.Stack.empty())
    {
      const int node = found.Stack.back();
      found.Stack.pop_back();
      for (const int next : star.Links[node])
      {
        if (found.Component[next] < 0 && star.Class[next] == cls)
        {
          found.Component[next] = count;
          found.Stack.push_back(next);
        }
      }
    }
    ++count;
    const auto at = std::lower_bound(found.Parts.begin(), found.Parts.end(), std::make_pair(cls, 0));
    if (at != found.Parts.end() && at->first == cls)
      ++at->second;
    else
      found.Parts.insert(at, { cls, 1 });
  }
}
} // namespace

bool FindStarViolation(const VertexStar& star, std::int32_t background, StarViolation& found)
{
  // Where no tissue is, the mesh has nothing (the gaps of the lattice may pinch there).
  if (std::all_of(star.Class.begin(), star.Class.end(), [&](std::int32_t c) { return c == background; }))
  {
    return false;
  }
  // Split classes first (the smallest label first): joining or trimming them often mends a ring too.
  CountClassParts(star, found);
  for (const auto& [cls, parts] : found.Parts)
  {
    if (parts > 1)
    {
      found.Split = true;
      found.Class = cls;
      return true;
    }
  }
  // A class's complement is the other classes' nodes: with two classes, the other one, whole.
  if (found.Parts.size() <= 2)
  {
    return false;
  }
  for (const auto& [cls, parts] : found.Parts)
  {
    const std::int32_t ring = cls;
    if (StarComponents(star, [&](int node) { return star.Class[node] != ring; }, found.Component) > 1)
    {
      found.Split = false;
      found.Class = cls;
      return true;
    }
  }
  return false;
}

StarLoader::StarLoader(const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets,
  const std::vector<TetNeighbours>& across, std::int32_t background,
  const std::vector<std::int32_t>& classes, int threads)
  : PointList(points)
  , TetList(tets)
  , Across(across)
  , Stars(tets, points.size(), threads)
  , Background(background)
  , Classes(classes)
{
}

bool StarLoader::IsUniform(PointId v) const
{
  const std::int64_t first = this->Stars.Start[v], last = this->Stars.Start[v + 1];
  if (first == last)
  {
    return true;
  }
  const std::int32_t cls = this->Classes[this->Stars.Tets[first]];
  for (std::int64_t i = first; i < last; ++i)
  {
    const std::int64_t t = this->Stars.Tets[i];
    if (this->Classes[t] != cls)
    {
      return false;
    }
    if (cls != this->Background)
      for (int j = 0; j < 4; ++j)
        if (this->TetList[t][j] != v && this->Across[t][j] < 0)
          return false;
  }
  return true;
}
void StarLoader::Load(PointId v, VertexStar& star, std::vector<int>& localOf) const
{
  const std::int64_t first = this->Stars.Start[v], last = this->Stars.Start[v + 1];
  star.Tets.assign(this->Stars.Tets.begin() + first, this->Stars.Tets.begin() + last);
  const int n = static_cast<int>(star.Tets.size());
  // The star is scratch reused from vertex to vertex: its lists keep their memory.
  if (star.Links.size() < std::size_t(n))
    star.Links.resize(n);
  for (int i = 0; i < n; ++i)
    star.Links[i].clear();
  star.Class.resize(n);
  for (int i = 0; i < n; ++i)
  {
    localOf[star.Tets[i]] = i;
    star.Class[i] = this->Classes[star.Tets[i]];
  }
  std::vector<OutsideFace> outside;
  for (int i = 0; i < n; ++i)
  {
    const Tet& tet = this->TetList[star.Tets[i]];
    for (int j = 0; j < 4; ++j)
    {
      if (tet[j] == v)
      {
        continue; // the face opposite v does not pass through it
      }
      const std::int64_t neighbour = this->Across[star.Tets[i]][j];
      if (neighbour >= 0)
      {
        star.Links[i].push_back(localOf[neighbour]);
        continue;
      }
      OutsideFace face{ star.Nodes(), i, { -1, -1 } };
      for (int k = 0, f = 0; k < 4; ++k)
        if (k != j && tet[k] != v)
          face.Far[f++] = tet[k];
      star.Class.push_back(this->Background);
      if (star.Links.size() < star.Class.size())
        star.Links.emplace_back();
      star.Links[face.Node].assign(1, i);
      star.Links[i].push_back(face.Node);
      outside.push_back(face);
    }
  }
  this->LinkOutside(v, star, outside);
  if (!outside.empty() && this->CoveredPieces(v, star) > 1)
  {
    // The mesh itself pinches at v: its pieces there are islands in one gap around them.
    for (std::size_t f = 1; f < outside.size(); ++f)
      LinkNodes(star, outside[f - 1].Node, outside[f].Node);
  }
  for (const std::int64_t t : star.Tets)
  {
    localOf[t] = -1;
  }
}
// The pieces of the mesh around v: its tets joined through shared edges or faces through v.
int StarLoader::CoveredPieces(PointId v, const VertexStar& star) const
{
  std::vector<PointId> far;
  for (const std::int64_t t : star.Tets)
    for (const PointId p : this->TetList[t])
      if (p != v)
        far.push_back(p);
  std::sort(far.begin(), far.end());
  far.erase(std::unique(far.begin(), far.end()), far.end());
  DisjointSets pieces(far.size());
  auto index = [&](PointId p) { return std::lower_bound(far.begin(), far.end(), p) - far.begin(); };
  int count = static_cast<int>(far.size());
  for (const std::int64_t t : star.Tets)
  {
    std::int64_t first = -1;
    for (const PointId p : this->TetList[t])
    {
      if (p == v)
        continue;
      if (first < 0)
        first = index(p);
      else if (pieces.Find(first) != pieces.Find(index(p)))
      {
        pieces.Join(first, index(p));
        --count;
      }
    }
  }
  return count;
}
// Links the outside faces that bound one gap: around each edge (v, w) the tets form chains
// whose ends are outside faces; going round the edge, two consecutive ends of different chains
// (or the two ends of the only chain) face the same gap.
void StarLoader::LinkOutside(PointId v, VertexStar& star, const std::vector<OutsideFace>& outside) const
{
  std::vector<std::pair<PointId, int>> byEdge; // (w, index in outside)
  for (int f = 0; f < static_cast<int>(outside.size()); ++f)
    for (const PointId w : outside[f].Far)
      byEdge.emplace_back(w, f);
  std::sort(byEdge.begin(), byEdge.end());
  for (std::size_t a = 0; a < byEdge.size();)
  {
    std::size_t b = a;
    while (b < byEdge.size() && byEdge[b].first == byEdge[a].first)
      ++b;
    std::vector<int> ends;
    for (std::size_t e = a; e < b; ++e)
      ends.push_back(byEdge[e].second);
    if (ends.size() == 2)
      LinkNodes(star, outside[ends[0]].Node, outside[ends[1]].Node);
    else if (ends.size() > 2)
      this->LinkAroundEdge(v, byEdge[a].first, star, outside, ends);
    a = b;
  }
}
// Where the mesh pinches along the edge (v, w), the ends are ordered by their angle about it.
void StarLoader::LinkAroundEdge(PointId v, PointId w, VertexStar& star,
  const std::vector<OutsideFace>& outside, std::vector<int>& ends) const
{
  const Eigen::Vector3d axis = (this->PointList[w] - this->PointList[v]).normalized();
  const Eigen::Vector3d u = axis.unitOrthogonal(), t = axis.cross(u);
  auto angle = [&](int f) {
    const OutsideFace& face = outside[f];
    const PointId x = face.Far[0] == w ? face.Far[1] : face.Far[0];
    const Eigen::Vector3d d = this->PointList[x] - this->PointList[v];
    return std::atan2(d.dot(t), d.dot(u));
  };
  std::sort(ends.begin(), ends.end(), [&](int a, int b) { return angle(a) < angle(b); });
  // The chain of each end: the tets containing w, joined through faces containing w.
  std::vector<int> chain;
  StarComponents(
    star,
    [&](int node) {
      // Outside-face nodes come after the tets: only a tet node may index star.Tets.
      if (!star.IsTet(node))
        return false;
      const Tet& tet = this->TetList[star.Tets[node]];
      return std::find(tet.begin(), tet.end(), w) != tet.end();
    },
    chain);
  const std::size_t count = ends.size();
  for (std::size_t e = 0; e < count; ++e)
  {
    const int a = ends[e], b = ends[(e + 1) % count];
    if (chain[outside[a].Tet] != chain[outside[b].Tet])
      LinkNodes(star, outside[a].Node, outside[b].Node);
  }
}
} // namespace cbc3d
