#include "cbc3d/lattice/RedGreenMesh.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/TetTopology.h"
#include "cbc3d/lattice/RedGreenTables.h"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>

namespace cbc3d
{
namespace
{
std::uint64_t EdgeKey(PointId a, PointId b)
{
  if (a > b)
  {
    std::swap(a, b);
  }
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b);
}

// When exactly two edges of one face are split, the face's third edge (which completes a green
// closure, cheaper than a red split); -1 otherwise.
int ThirdEdgeOfFace(std::uint8_t mask)
{
  constexpr std::array<std::uint8_t, 4> faceEdges = { 0b000111, 0b011001, 0b110010, 0b101100 };
  for (const std::uint8_t face : faceEdges)
  {
    const std::uint8_t missing = face & ~mask;
    if ((mask & ~face) == 0 && missing != 0 && (missing & (missing - 1)) == 0)
    {
      for (int e = 0; e < 6; ++e)
      {
        if (missing == (1u << e))
        {
          return e;
        }
      }
    }
  }
  return -1;
}

// Every edge of a tet, as a split mask: PointsOf then looks up all six midpoints.
constexpr std::uint8_t EveryEdge = 0x3f;

// The split edges of a tet from its local points (corners, then edge midpoints or -1).
std::uint8_t SplitEdges(const std::array<PointId, 10>& local)
{
  std::uint8_t mask = 0;
  for (int e = 0; e < 6; ++e)
  {
    mask |= local[4 + e] >= 0 ? static_cast<std::uint8_t>(1u << e) : 0;
  }
  return mask;
}

// Closing and building the mesh walk every red, a second or more on large meshes: they ask
// for a stop every so many reds.
bool StopAt(std::size_t red, const std::function<bool()>& keepGoing)
{
  return red % 2048 == 0 && keepGoing && !keepGoing();
}
} // namespace

RedGreenMesh::RedGreenMesh(const TetMesh& roots)
  : PointList(roots.Points)
  , TouchedAt(roots.Points.size(), 0)
  , ClosedAt(roots.Tets.size(), 0)
  , ParentEdge(roots.Points.size(), { -1, -1 })
{
  this->RedList.reserve(roots.Tets.size());
  for (const Tet& tet : roots.Tets)
  {
    this->RedList.push_back(RedTet{ tet, 0, true });
  }
}

void RedGreenMesh::Touch(PointId p)
{
  this->TouchedAt[p] = this->Clock;
  for (const PointId end : this->ParentEdge[p])
  {
    if (end >= 0)
    {
      this->TouchedAt[end] = this->Clock;
    }
  }
}

bool RedGreenMesh::MayHaveChanged(std::size_t red) const
{
  const std::uint64_t closed = this->ClosedAt[red];
  const Tet& tet = this->RedList[red].Points;
  return closed == 0 || std::any_of(tet.begin(), tet.end(), [&](PointId p) { return this->TouchedAt[p] > closed; });
}

PointId RedGreenMesh::FindMidpoint(PointId a, PointId b) const
{
  return this->Midpoints.Find(EdgeKey(a, b));
}

PointId RedGreenMesh::Midpoint(PointId a, PointId b)
{
  CheckPointCount(this->PointList.size() + 1);
  const auto inserted = this->Midpoints.Insert(EdgeKey(a, b), PointId(this->PointList.size()));
  if (inserted.second)
  {
    this->PointList.push_back(0.5 * (this->PointList[a] + this->PointList[b]));
    ++this->Clock;
    this->TouchedAt.push_back(this->Clock);
    this->ParentEdge.push_back({ a, b });
    this->Touch(a);
    this->Touch(b);
  }
  return inserted.first;
}

std::uint8_t RedGreenMesh::SplitMask(const Tet& tet) const
{
  return SplitEdges(this->PointsOf(tet, EveryEdge));
}

RedGreenMesh::LocalPoints RedGreenMesh::PointsOf(const Tet& tet, std::uint8_t mask) const
{
  LocalPoints local;
  for (int v = 0; v < 4; ++v)
  {
    local[v] = tet[v];
  }
  for (int e = 0; e < 6; ++e)
  {
    local[4 + e] = mask & (1u << e) ? this->FindMidpoint(tet[TetEdges[e][0]], tet[TetEdges[e][1]]) : -1;
  }
  return local;
}

bool RedGreenMesh::HasClosure(const Tet& tet) const
{
  // Each midpoint looked up once: the mask, then the closure's edges, from the same points.
  const LocalPoints local = this->PointsOf(tet, EveryEdge);
  const std::uint8_t mask = SplitEdges(local);
  if (mask == 0)
  {
    return true; // the tet itself, none of whose edges is split: most leaves
  }
  const std::vector<LocalTet>* closure = GreenClosure(mask);
  if (!closure)
  {
    return false;
  }
  // No child edge may be split: that would leave a point hanging on it.
  for (const LocalTet& child : *closure)
  {
    for (const auto& edge : TetEdges)
    {
      if (this->FindMidpoint(local[child[edge[0]]], local[child[edge[1]]]) >= 0)
      {
        return false;
      }
    }
  }
  return true;
}

void RedGreenMesh::SplitRed(std::size_t red)
{
  const Tet tet = this->RedList[red].Points;
  const int level = this->RedList[red].Level;
  LocalPoints local;
  for (int v = 0; v < 4; ++v)
  {
    local[v] = tet[v];
  }
  for (int e = 0; e < 6; ++e)
  {
    local[4 + e] = this->Midpoint(tet[TetEdges[e][0]], tet[TetEdges[e][1]]);
  }
  // The shortest of the three diagonals between midpoints of opposite edges.
  int diagonal = 0;
  double shortest = 0.0;
  for (int d = 0; d < 3; ++d)
  {
    const double length = (this->PointList[local[4 + d]] - this->PointList[local[4 + OppositeEdge[d]]]).squaredNorm();
    if (d == 0 || length < shortest)
    {
      shortest = length;
      diagonal = d;
    }
  }
  this->RedList[red].Leaf = false;
  for (const LocalTet& child : RedChildren(diagonal))
  {
    this->RedList.push_back(
      RedTet{ Tet{ local[child[0]], local[child[1]], local[child[2]], local[child[3]] }, level + 1, true });
    this->ClosedAt.push_back(0);
  }
}

bool RedGreenMesh::Close(const std::function<bool()>& keepGoing)
{
  bool changed = true;
  while (changed)
  {
    changed = false;
    const std::size_t count = this->RedList.size();
    for (std::size_t red = 0; red < count; ++red)
    {
      if (StopAt(red, keepGoing))
      {
        return false;
      }
      if (!this->RedList[red].Leaf || !this->MayHaveChanged(red))
      {
        continue;
      }
      const Tet tet = this->RedList[red].Points;
      if (this->HasClosure(tet))
      {
        this->ClosedAt[red] = this->Clock;
      }
      else
      {
        const int third = ThirdEdgeOfFace(this->SplitMask(tet));
        if (third >= 0)
        {
          this->Midpoint(tet[TetEdges[third][0]], tet[TetEdges[third][1]]);
          changed = true;
          continue;
        }
        this->SplitRed(red);
        changed = true;
      }
    }
  }
  return true;
}

bool RedGreenMesh::BuildConforming(std::vector<Tet>& tets, std::vector<std::int64_t>& source,
  const std::function<bool()>& keepGoing, std::vector<std::uint8_t>* leafMasks, int threads) const
{
  // Each leaf's split edges and its number of children first, then the children written from
  // each leaf's offset: both passes on the threads, in blocks so that a stop is seen soon, and
  // the same list as one pass over the reds in order.
  const std::int64_t count = static_cast<std::int64_t>(this->RedList.size());
  const int threadCount = ThreadCount(threads);
  constexpr std::int64_t Block = std::int64_t(1) << 16;
  std::vector<std::uint8_t> masks(count, NotLeaf);
  std::vector<std::int64_t> offset(count + 1, 0);
  for (std::int64_t begin = 0; begin < count; begin += Block)
  {
    if (keepGoing && !keepGoing())
    {
      return false;
    }
#pragma omp parallel for schedule(static) num_threads(threadCount)
    for (std::int64_t red = begin; red < std::min(count, begin + Block); ++red)
    {
      if (this->RedList[red].Leaf)
      {
        masks[red] = this->SplitMask(this->RedList[red].Points);
        offset[red + 1] = static_cast<std::int64_t>(GreenClosure(masks[red])->size());
      }
    }
  }
  std::partial_sum(offset.begin(), offset.end(), offset.begin());
  tets.resize(offset[count]);
  source.resize(offset[count]);
#pragma omp parallel for schedule(static) num_threads(threadCount)
  for (std::int64_t red = 0; red < count; ++red)
  {
    if (masks[red] == NotLeaf)
    {
      continue;
    }
    const LocalPoints local = this->PointsOf(this->RedList[red].Points, masks[red]);
    std::int64_t at = offset[red];
    for (const LocalTet& child : *GreenClosure(masks[red]))
    {
      tets[at] = Tet{ local[child[0]], local[child[1]], local[child[2]], local[child[3]] };
      source[at++] = red;
    }
  }
  if (leafMasks)
  {
    *leafMasks = std::move(masks);
  }
  return true;
}

double RedGreenMesh::LongestEdge(std::size_t red) const
{
  return LongestEdgeOf(this->PointList, this->RedList[red].Points);
}

double RedGreenMesh::ShortestEdge(std::size_t red) const
{
  const Tet& tet = this->RedList[red].Points;
  double shortest = std::numeric_limits<double>::infinity();
  for (const auto& edge : TetEdges)
  {
    shortest = std::min(shortest, (this->PointList[tet[edge[0]]] - this->PointList[tet[edge[1]]]).norm());
  }
  return shortest;
}
} // namespace cbc3d
