#ifndef cbc3d_InteriorSmoothing_h
#define cbc3d_InteriorSmoothing_h

#include "cbc3d/base/PointTets.h"
#include "cbc3d/base/TetMesh.h"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace cbc3d
{
/// Smart Laplacian smoothing over a fixed tet list: a movable vertex goes to the mean of the
/// centroids of its tets where that improves the worst dihedral angle among those tets (the
/// one nearest 0 or 180 degrees), and stays where it is otherwise; so no tet around a moved
/// vertex gets worse than that vertex's worst, and none inverts. Used between deformation
/// steps: it gives surface vertices held back by thin tets room to move on the next step.
class InteriorSmoothing
{
public:
  /// `edgeLimits` (one per tet, mm; 0 = none), where given: no move makes a tet's edge longer.
  /// The tets around each point are listed on `threads` threads.
  InteriorSmoothing(const std::vector<Tet>& tets, std::size_t pointCount,
    const std::vector<double>* edgeLimits = nullptr, int threads = 1);

  /// Sweeps over the movable points in point order (a Gauss-Seidel sweep: each move sees the
  /// moves before it), until a sweep moves none or `sweeps` are done. Returns how many moves it
  /// made. On `threads`, level by level (Levels): the same moves as one thread.
  std::size_t Smooth(
    std::vector<Eigen::Vector3d>& points, const std::vector<char>& movable, int sweeps, int threads = 1) const;

  /// Per point, whether it shares a tet with a point that `marked` holds for (itself
  /// included), found on the threads.
  std::vector<char> SharingATetWith(const std::vector<char>& marked, int threads) const;

private:
  /// The movable points in levels: points of one level share no tet, and of two points that
  /// do, the earlier in point order is in an earlier level. So moving a level's points at once,
  /// level after level, reads and writes what the sweep in point order would.
  std::vector<std::vector<PointId>> Levels(const std::vector<char>& movable) const;
  /// Moves p to the mean of its tets' centroids if that makes its worst tet better; keeps the
  /// tets' `badness` up to date. `trial`: scratch.
  bool TryMove(PointId p, std::vector<Eigen::Vector3d>& x, std::vector<double>& badness,
    std::vector<double>& trial) const;
  /// Whether the tets around p keep their edge limits.
  bool WithinEdgeLimits(PointId p, const std::vector<Eigen::Vector3d>& x) const;

  const std::vector<Tet>& Tets;
  const std::vector<double>* EdgeLimits;
  PointTets Around; // the tets around each point
};
} // namespace cbc3d

#endif
