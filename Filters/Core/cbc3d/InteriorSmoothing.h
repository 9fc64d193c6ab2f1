#ifndef cbc3d_InteriorSmoothing_h
#define cbc3d_InteriorSmoothing_h

#include "cbc3d/PointTets.h"
#include "cbc3d/TetMesh.h"

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
  explicit InteriorSmoothing(const std::vector<Tet>& tets, std::size_t pointCount);

  /// Sweeps over the movable points in point order (serial, so the result does not depend on
  /// threads; the tets' starting quality is measured on `threads`), until a sweep moves none
  /// or `sweeps` are done. Returns how many moves it made.
  std::size_t Smooth(
    std::vector<Eigen::Vector3d>& points, const std::vector<char>& movable, int sweeps, int threads = 1) const;

  /// Per point, whether it shares a tet with a point that `marked` holds for (itself
  /// included), found on the threads.
  std::vector<char> SharingATetWith(const std::vector<char>& marked, int threads) const;

private:
  const std::vector<Tet>& Tets;
  PointTets Around; // the tets around each point
};
} // namespace cbc3d

#endif
