#include "cbc3d/PointGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

Eigen::Matrix<std::int64_t, 3, 1> PointGrid::QueryCellOf(const Eigen::Vector3d& x) const
{
  Eigen::Matrix<std::int64_t, 3, 1> c;
  for (int a = 0; a < 3; ++a)
  {
    const double f = std::floor((x[a] - this->Origin[a]) / this->Cell);
    c[a] = std::isnan(f) ? 0 : static_cast<std::int64_t>(std::clamp(f, -1e9, 1e9));
  }
  return c;
}

double PointGrid::OutsideDistance(
  const Eigen::Vector3d& x, const Eigen::Matrix<std::int64_t, 3, 1>& centre, std::int64_t k) const
{
  double nearest = std::numeric_limits<double>::infinity();
  double scale = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    if (centre[a] - k > 0) // grid cells below the cube
    {
      nearest = std::min(nearest, x[a] - (this->Origin[a] + double(centre[a] - k) * this->Cell));
    }
    if (centre[a] + k < this->Size[a] - 1) // and above it
    {
      nearest = std::min(nearest, this->Origin[a] + double(centre[a] + k + 1) * this->Cell - x[a]);
    }
    scale = std::max({ scale, std::abs(x[a]), std::abs(this->Origin[a]) });
  }
  // A point on a cell's face may have been bucketed a rounding error to either side of it.
  return nearest - (1e-6 * this->Cell + 1e-12 * scale);
}

int PointGrid::NearestAny(const Eigen::Vector3d& x) const
{
  return this->Nearest(x, std::numeric_limits<double>::infinity());
}
} // namespace cbc3d
