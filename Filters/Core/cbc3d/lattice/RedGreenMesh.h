#ifndef cbc3d_RedGreenMesh_h
#define cbc3d_RedGreenMesh_h

#include "cbc3d/base/TetMesh.h"
#include "cbc3d/lattice/EdgeMidpoints.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace cbc3d
{
/// A red-green refinement hierarchy over a starting mesh (the roots, level 0).
///
/// Red tets are split 1:8 (children: level + 1) and stay in the hierarchy; the mesh is the red
/// leaves, each closed by a green split when neighbours have split some of its edges. Green
/// tets are never split: when one would need refining, its red parent (the leaf) is split.
/// Every new point is an edge midpoint, shared by all tets around the edge, so the mesh stays
/// conforming.
class RedGreenMesh
{
public:
  struct RedTet
  {
    Tet Points;
    int Level = 0;
    bool Leaf = true;
  };

  explicit RedGreenMesh(const TetMesh& roots);

  const std::vector<Eigen::Vector3d>& Points() const { return this->PointList; }
  const std::vector<RedTet>& Reds() const { return this->RedList; }

  /// Splits a red leaf 1:8 along its shortest inner diagonal.
  void SplitRed(std::size_t red);

  /// Splits edge (a, b) of a red leaf at its midpoint: the leaves around it take a green
  /// closure, or a red split where none fits, at the next Close(). Returns the midpoint.
  PointId SplitEdge(PointId a, PointId b) { return this->Midpoint(a, b); }

  /// Closes the mesh: a leaf with two split edges on one face gets the face's third edge split
  /// too (a green closure, as in CBC3D; far cheaper than a red split, which would split the
  /// neighbours' edges in turn), and any other leaf without a green closure none of whose edges
  /// is split is red-split, until every leaf has one. Asks `keepGoing` every few thousand reds
  /// and returns false, the closure unfinished, when it says stop.
  bool Close(const std::function<bool()>& keepGoing = nullptr);

  /// The conforming mesh: every leaf, green-split where its edges are split. `source[i]` is
  /// the red leaf that final tet i comes from; a leaf's tets come together, in the order of the
  /// reds. With `leafMasks`, each red's split edges (bit e: edge TetEdges[e]) where it is a
  /// leaf, NotLeaf where not: a leaf with the same mask in two builds made the same tets, in
  /// the same order. Call after Close(). Asks `keepGoing` (from the calling thread) every few
  /// tens of thousands of reds; returns false, the mesh unfinished, when it says stop. The
  /// same tets for any number of `threads`.
  bool BuildConforming(std::vector<Tet>& tets, std::vector<std::int64_t>& source,
    const std::function<bool()>& keepGoing = nullptr, std::vector<std::uint8_t>* leafMasks = nullptr,
    int threads = 1) const;
  static constexpr std::uint8_t NotLeaf = 0xff;

  /// The longest and the shortest edge of a red tet.
  double LongestEdge(std::size_t red) const;
  double ShortestEdge(std::size_t red) const;

private:
  // The corners and edge midpoints of a tet, in local point order (see RedGreenTables.h).
  using LocalPoints = std::array<PointId, 10>;

  PointId FindMidpoint(PointId a, PointId b) const;
  PointId Midpoint(PointId a, PointId b);
  std::uint8_t SplitMask(const Tet& tet) const;
  /// A tet's local points: its corners, and the midpoints of the edges `mask` says are split
  /// (-1 for the others).
  LocalPoints PointsOf(const Tet& tet, std::uint8_t mask) const;
  bool HasClosure(const Tet& tet) const;

  /// Whether a leaf already found closed may have lost its closure: a new midpoint changes the
  /// closures only of tets with its edge's points among their corners and edge midpoints, and
  /// each of those tets has a corner among the edge's points or their parent edges' points.
  bool MayHaveChanged(std::size_t red) const;
  void Touch(PointId p);

  std::vector<Eigen::Vector3d> PointList;
  std::vector<RedTet> RedList;
  EdgeMidpoints Midpoints;
  // Closure bookkeeping: a clock that ticks with every new midpoint, the tick at which each
  // point was last touched by one, each red's tick when it was last found closed (0: never),
  // and each point's parent edge (-1 for the roots' points).
  std::uint64_t Clock = 1;
  std::vector<std::uint64_t> TouchedAt;
  std::vector<std::uint64_t> ClosedAt;
  std::vector<std::array<PointId, 2>> ParentEdge;
};
} // namespace cbc3d

#endif
