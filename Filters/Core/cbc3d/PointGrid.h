#ifndef cbc3d_PointGrid_h
#define cbc3d_PointGrid_h

#include <Eigen/Core>

#include <cstdint>
#include <utility>
#include <vector>

namespace cbc3d
{
/// Points bucketed on a uniform grid, for nearest-point queries within a radius. Holds a
/// reference to the points: they must outlive the grid and stay in place.
class PointGrid
{
public:
  PointGrid(const std::vector<Eigen::Vector3d>& points, double cell);

  /// The nearest point within `radius` that `accept(index)` takes; -1 if none. Ties go to the
  /// lower index, so the answer does not depend on the order of the search.
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
  Eigen::Vector3i CellOf(const Eigen::Vector3d& x) const
  {
    return (x / this->Cell).array().floor().cast<int>();
  }
  static std::int64_t Key(const Eigen::Vector3i& c)
  {
    return (std::int64_t(c[0]) + (1 << 20)) + ((std::int64_t(c[1]) + (1 << 20)) << 21) +
      ((std::int64_t(c[2]) + (1 << 20)) << 42);
  }
  // The entries of one cell: a range of the sorted (key, index) list.
  std::pair<const std::pair<std::int64_t, int>*, const std::pair<std::int64_t, int>*> CellEntries(
    const Eigen::Vector3i& c) const;

  const std::vector<Eigen::Vector3d>& Points;
  double Cell;
  std::vector<std::pair<std::int64_t, int>> Entries;
};

template <typename Accept>
int PointGrid::Nearest(const Eigen::Vector3d& x, double radius, const Accept& accept) const
{
  const Eigen::Vector3i lo = this->CellOf(x - Eigen::Vector3d::Constant(radius));
  const Eigen::Vector3i hi = this->CellOf(x + Eigen::Vector3d::Constant(radius));
  int best = -1;
  double bestDistance = radius * radius;
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i)
      {
        const auto range = this->CellEntries(Eigen::Vector3i(i, j, k));
        for (auto it = range.first; it != range.second; ++it)
        {
          const double distance = (this->Points[it->second] - x).squaredNorm();
          if ((distance < bestDistance || (distance == bestDistance && (best < 0 || it->second < best))) &&
            accept(it->second))
          {
            best = it->second;
            bestDistance = distance;
          }
        }
      }
  return best;
}
} // namespace cbc3d

#endif
