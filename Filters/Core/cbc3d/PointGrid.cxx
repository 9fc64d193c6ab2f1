#include "cbc3d/PointGrid.h"

#include <algorithm>
#include <cmath>

namespace cbc3d
{
PointGrid::PointGrid(const std::vector<Eigen::Vector3d>& points, double cell)
  : Points(points)
  , Cell(cell)
{
  if (points.empty())
  {
    return;
  }
  Eigen::Vector3d lower = points[0], upper = points[0];
  for (const Eigen::Vector3d& p : points)
  {
    lower = lower.cwiseMin(p);
    upper = upper.cwiseMax(p);
  }
  this->Origin = lower;
  // Cells of at least `cell`, and not more cells than about 8 per point, so that a grid over
  // a few scattered points stays small.
  const Eigen::Vector3d extent = upper - lower;
  const double budget = 8.0 * double(points.size()) + 64.0;
  while (((extent / this->Cell).array().floor() + 1.0).prod() > budget)
  {
    this->Cell *= 2.0;
  }
  this->Size = ((extent / this->Cell).array().floor() + 1.0).cast<int>();
  const std::int64_t cells = std::int64_t(this->Size[0]) * this->Size[1] * this->Size[2];
  std::vector<std::int64_t> cellOf(points.size());
  this->CellStart.assign(cells + 1, 0);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const Eigen::Vector3i c = this->CellOf(points[i]);
    cellOf[i] = (std::int64_t(c[2]) * this->Size[1] + c[1]) * this->Size[0] + c[0];
    ++this->CellStart[cellOf[i] + 1];
  }
  for (std::int64_t c = 0; c < cells; ++c)
  {
    this->CellStart[c + 1] += this->CellStart[c];
  }
  // Within a cell, points keep ascending order (a stable counting sort).
  std::vector<int> next(this->CellStart.begin(), this->CellStart.end() - 1);
  this->Sorted.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    this->Sorted[next[cellOf[i]]++] = static_cast<int>(i);
  }
}

Eigen::Vector3i PointGrid::CellOf(const Eigen::Vector3d& x) const
{
  Eigen::Vector3i c;
  for (int a = 0; a < 3; ++a)
  {
    const double f = std::floor((x[a] - this->Origin[a]) / this->Cell);
    c[a] = static_cast<int>(std::clamp(f, 0.0, double(this->Size[a] - 1)));
  }
  return c;
}

int PointGrid::NearestAny(const Eigen::Vector3d& x) const
{
  if (this->Sorted.empty())
  {
    return -1;
  }
  // Exact: a point found within r is the nearest, since a nearer one lies within r too.
  int nearest = -1;
  for (double radius = this->Cell; nearest < 0; radius *= 2.0)
  {
    nearest = this->NearestInCube(x, radius, [](int) { return true; });
  }
  return nearest;
}
} // namespace cbc3d
