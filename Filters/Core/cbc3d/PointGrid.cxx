#include "cbc3d/PointGrid.h"

#include <algorithm>

namespace cbc3d
{
PointGrid::PointGrid(const std::vector<Eigen::Vector3d>& points, double cell)
  : Points(points)
  , Cell(cell)
{
  this->Entries.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    this->Entries.emplace_back(this->Key(this->CellOf(points[i])), static_cast<int>(i));
  }
  std::sort(this->Entries.begin(), this->Entries.end());
}

std::pair<const std::pair<std::int64_t, int>*, const std::pair<std::int64_t, int>*>
PointGrid::CellEntries(const Eigen::Vector3i& c) const
{
  const std::int64_t key = this->Key(c);
  const auto first = std::lower_bound(this->Entries.begin(), this->Entries.end(), std::make_pair(key, -1));
  auto last = first;
  while (last != this->Entries.end() && last->first == key)
  {
    ++last;
  }
  return { this->Entries.data() + (first - this->Entries.begin()),
    this->Entries.data() + (last - this->Entries.begin()) };
}

int PointGrid::NearestAny(const Eigen::Vector3d& x) const
{
  if (this->Entries.empty())
  {
    return -1;
  }
  // Exact: a point found within r is the nearest, since a nearer one lies within r too.
  int nearest = -1;
  for (double radius = this->Cell; nearest < 0; radius *= 2.0)
  {
    nearest = this->Nearest(x, radius);
  }
  return nearest;
}
} // namespace cbc3d
