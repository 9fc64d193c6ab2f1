#ifndef cbc3d_VertexStar_h
#define cbc3d_VertexStar_h

#include "cbc3d/base/PointTets.h"
#include "cbc3d/base/TetMesh.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace cbc3d
{
/// The tets around one vertex as a graph: two are linked when they share a face through the
/// vertex. Each face on the mesh boundary through the vertex is an outside node, linked to its
/// tet and to the outside faces next to it across the gap it bounds (the mesh need not be
/// convex: the lattice leaves out tets with no tissue).
struct VertexStar
{
  std::vector<std::int64_t> Tets;      // node i < Tets.size() is tet Tets[i]; then outside nodes
  std::vector<std::vector<int>> Links; // per node, its linked nodes
  std::vector<std::int32_t> Class;     // per node

  int Nodes() const { return static_cast<int>(this->Class.size()); } // Links may hold more
  bool IsTet(int node) const { return node < static_cast<int>(this->Tets.size()); }
};

/// Components of the star's nodes for which `member` holds; returns their count, fills
/// `component` (-1 for non-members), numbered in node order.
template <typename Member>
int StarComponents(const VertexStar& star, Member member, std::vector<int>& component)
{
  component.assign(star.Nodes(), -1);
  int count = 0;
  std::vector<int> stack;
  for (int seed = 0; seed < star.Nodes(); ++seed)
  {
    if (component[seed] >= 0 || !member(seed))
    {
      continue;
    }
    component[seed] = count;
    stack.assign(1, seed);
    while (!stack.empty())
    {
      const int node = stack.back();
      stack.pop_back();
      for (const int next : star.Links[node])
      {
        if (component[next] < 0 && member(next))
        {
          component[next] = count;
          stack.push_back(next);
        }
      }
    }
    ++count;
  }
  return count;
}

inline void LinkNodes(VertexStar& star, int a, int b)
{
  star.Links[a].push_back(b);
  star.Links[b].push_back(a);
}

/// A class that is not manifold around a vertex: in several parts there, or (a ring) its
/// complement is.
struct StarViolation
{
  bool Split = false;     // the class is in several parts (else: its complement is)
  std::int32_t Class = 0;
  // Scratch of the search, kept between searches: stars are searched by the million.
  std::vector<int> Component, Stack;
  std::vector<std::pair<std::int32_t, int>> Parts; // (class, its parts), ascending class
};

/// The first violation at the star's vertex, if any: split classes first (the smallest label
/// first), then rings. A star of the background alone has none (the lattice's gaps may pinch
/// where no tissue is).
bool FindStarViolation(const VertexStar& star, std::int32_t background, StarViolation& found);

/// Builds the stars of a mesh's vertices from the tets' current classes (read, never written).
class StarLoader
{
public:
  /// The tets around each vertex are listed on `threads` threads.
  StarLoader(const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets,
    const std::vector<TetNeighbours>& across, std::int32_t background,
    const std::vector<std::int32_t>& classes, int threads = 1);

  /// The star of v, into `star` (scratch reused from vertex to vertex), with the caller's
  /// tet -> node scratch `localOf` (all -1, and left so).
  void Load(PointId v, VertexStar& star, std::vector<int>& localOf) const;
  /// One class all round, and no tissue meeting the mesh boundary (where the gaps could pinch).
  bool IsUniform(PointId v) const;

private:
  // An outside face through the star's vertex: its node, its tet's node and its far vertices.
  struct OutsideFace
  {
    int Node, Tet;
    PointId Far[2];
  };
  int CoveredPieces(PointId v, const VertexStar& star) const;
  void LinkOutside(PointId v, VertexStar& star, const std::vector<OutsideFace>& outside) const;
  void LinkAroundEdge(PointId v, PointId w, VertexStar& star, const std::vector<OutsideFace>& outside,
    std::vector<int>& ends) const;

  const std::vector<Eigen::Vector3d>& PointList;
  const std::vector<Tet>& TetList;
  const std::vector<TetNeighbours>& Across;
  PointTets Stars; // the tets around each point
  std::int32_t Background;
  const std::vector<std::int32_t>& Classes;
};
} // namespace cbc3d

#endif
