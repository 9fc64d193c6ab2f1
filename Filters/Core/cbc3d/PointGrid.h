#ifndef cbc3d_PointGrid_h
#define cbc3d_PointGrid_h

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace cbc3d
{
/// Points bucketed on a uniform grid over their bounding box, for nearest-point queries within
/// a radius. Holds a reference to the points: they must outlive the grid and stay in place.
class PointGrid
{
public:
  PointGrid(const std::vector<Eigen::Vector3d>& points, double cell);

  /// The nearest point within `radius` that `accept(index)` takes; -1 if none. Ties go to the
  /// lower index, so the answer does not depend on the order of the search. The search widens
  /// from one cell, doubling, up to `radius`: a large radius costs little where a point is near.
  template <typename Accept>
  int Nearest(const Eigen::Vector3d& x, double radius, const Accept& accept) const;

  /// The nearest point within `radius`; -1 if none.
  int Nearest(const Eigen::Vector3d& x, double radius) const
  {
    return this->Nearest(x, radius, [](int) { return true; });
  }

  /// The nearest point at any distance (the search radius doubles until one is found); -1 only
  /// when the grid is empty.
  int NearestAny(const Eigen::Vector3d& x) const;

private:
  // The cell of x along each axis, clamped to the grid (a point outside lies in no cell, so a
  // clamped range of cells still holds every point within reach).
  Eigen::Vector3i CellOf(const Eigen::Vector3d& x) const;

  // The nearest accepted point within `radius`, over every cell of the cube around x.
  template <typename Accept>
  int NearestInCube(const Eigen::Vector3d& x, double radius, const Accept& accept) const;

  const std::vector<Eigen::Vector3d>& Points;
  double Cell;
  Eigen::Vector3d Origin = Eigen::Vector3d::Zero();
  Eigen::Vector3i Size = Eigen::Vector3i::Zero();
  std::vector<int> CellStart; // points of cell c: Sorted[CellStart[c] .. CellStart[c + 1])
  std::vector<int> Sorted;
};

template <typename Accept>
int PointGrid::Nearest(const Eigen::Vector3d& x, double radius, const Accept& accept) const
{
  // Exact: an accepted point found within r is the nearest, since a nearer one (or an equal
  // one of lower index) lies within r too.
  for (double r = this->Cell; r < radius; r *= 2.0)
  {
    const int found = this->NearestInCube(x, r, accept);
    if (found >= 0)
    {
      return found;
    }
  }
  return this->NearestInCube(x, radius, accept);
}

template <typename Accept>
int PointGrid::NearestInCube(const Eigen::Vector3d& x, double radius, const Accept& accept) const
{
  if (this->Sorted.empty())
  {
    return -1;
  }
  const Eigen::Vector3i lo = this->CellOf(x - Eigen::Vector3d::Constant(radius));
  const Eigen::Vector3i hi = this->CellOf(x + Eigen::Vector3d::Constant(radius));
  int best = -1;
  double bestDistance = radius * radius;
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
    {
      const std::int64_t row = (std::int64_t(k) * this->Size[1] + j) * this->Size[0];
      for (int s = this->CellStart[row + lo[0]]; s < this->CellStart[row + hi[0] + 1]; ++s)
      {
        const int index = this->Sorted[s];
        const double distance = (this->Points[index] - x).squaredNorm();
        if ((distance < bestDistance || (distance == bestDistance && (best < 0 || index < best))) &&
          accept(index))
        {
          best = index;
          bestDistance = distance;
        }
      }
    }
  return best;
}
} // namespace cbc3d

#endif
