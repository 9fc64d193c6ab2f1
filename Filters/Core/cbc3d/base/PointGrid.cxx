#include "cbc3d/base/PointGrid.h"

#include "cbc3d/base/Parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cbc3d
{
PointGrid::PointGrid(const std::vector<Eigen::Vector3d>& points, double cell, int threads)
  : Points(points)
  , Cell(cell)
{
  if (points.empty())
  {
    return;
  }
  const std::int64_t count = static_cast<std::int64_t>(points.size());
  const int workers = ThreadCount(threads);
  // The bounding box: minima and maxima are exact in any order.
  Eigen::Vector3d lower = points[0], upper = points[0];
#pragma omp parallel num_threads(workers)
  {
    Eigen::Vector3d low = points[0], high = points[0];
#pragma omp for schedule(static) nowait
    for (std::int64_t i = 0; i < count; ++i)
    {
      low = low.cwiseMin(points[i]);
      high = high.cwiseMax(points[i]);
    }
#pragma omp critical(cbc3d_PointGridBounds)
    {
      lower = lower.cwiseMin(low);
      upper = upper.cwiseMax(high);
    }
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
#pragma omp parallel for schedule(static) num_threads(workers)
  for (std::int64_t i = 0; i < count; ++i)
    cellOf[i] = this->CellIndex(points[i]);
  this->CellStart.assign(cells + 1, 0);
  for (const std::int64_t c : cellOf)
    ++this->CellStart[c + 1];
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

namespace
{
// floor(t) clamped to [lowest, highest], 0 for NaN, from one truncation: this runs for every
// query and point, and std::floor (a library call, or a long inline sequence without SSE4.1)
// followed by a clamp in doubles cost 2% of the brain's instructions more.
std::int64_t ClampedFloor(double t, std::int64_t lowest, std::int64_t highest)
{
  if (!(t > double(lowest)))
  {
    return t <= double(lowest) ? lowest : 0; // below the range, or NaN
  }
  if (t >= double(highest))
  {
    return highest;
  }
  const std::int64_t truncated = static_cast<std::int64_t>(t); // towards zero
  return truncated > t ? truncated - 1 : truncated;
}
} // namespace

Eigen::Vector3i PointGrid::CellOf(const Eigen::Vector3d& x) const
{
  Eigen::Vector3i c;
  for (int a = 0; a < 3; ++a)
  {
    c[a] = static_cast<int>(ClampedFloor((x[a] - this->Origin[a]) / this->Cell, 0, this->Size[a] - 1));
  }
  return c;
}

Eigen::Matrix<std::int64_t, 3, 1> PointGrid::QueryCellOf(const Eigen::Vector3d& x) const
{
  constexpr std::int64_t far = 1000000000;
  Eigen::Matrix<std::int64_t, 3, 1> c;
  for (int a = 0; a < 3; ++a)
  {
    c[a] = ClampedFloor((x[a] - this->Origin[a]) / this->Cell, -far, far);
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

std::int64_t PointGrid::CellIndex(const Eigen::Vector3d& x) const
{
  const Eigen::Vector3i c = this->CellOf(x);
  return (std::int64_t(c[2]) * this->Size[1] + c[1]) * this->Size[0] + c[0];
}

void PointGrid::PointsNear(const Eigen::Vector3d& x, double radius, std::vector<int>& found) const
{
  found.clear();
  Eigen::Matrix<std::int64_t, 3, 1> lo, hi;
  for (int a = 0; a < 3; ++a)
  {
    // One cell more on each side: a point on a cell's face may sit a rounding error over it.
    lo[a] = std::max<std::int64_t>(
      0, static_cast<std::int64_t>(std::floor((x[a] - radius - this->Origin[a]) / this->Cell)) - 1);
    hi[a] = std::min<std::int64_t>(this->Size[a] - 1,
      static_cast<std::int64_t>(std::floor((x[a] + radius - this->Origin[a]) / this->Cell)) + 1);
    if (lo[a] > hi[a])
      return;
  }
  const double limit = radius * radius;
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
    {
      const std::int64_t row = (z * this->Size[1] + y) * this->Size[0];
      for (int s = this->CellStart[row + lo[0]]; s < this->CellStart[row + hi[0] + 1]; ++s)
        if ((this->Points[this->Sorted[s]] - x).squaredNorm() <= limit)
          found.push_back(this->Sorted[s]);
    }
}

bool PointGrid::GroupByCell(
  const std::vector<Eigen::Vector3d>& queries, int minimumPerCell, QueryGroups& groups, int threads) const
{
  const std::int64_t count = static_cast<std::int64_t>(queries.size());
  const std::int64_t cells = static_cast<std::int64_t>(this->CellStart.size()) - 1;
  std::vector<std::int64_t> cellOf(queries.size());
#pragma omp parallel for schedule(static) num_threads(ThreadCount(threads))
  for (std::int64_t i = 0; i < count; ++i)
    cellOf[i] = this->CellIndex(queries[i]);
  std::vector<int> start(cells + 1, 0);
  for (std::int64_t i = 0; i < count; ++i)
    ++start[cellOf[i] + 1];
  groups.Start.assign(1, 0);
  for (std::int64_t c = 0; c < cells; ++c)
  {
    if (start[c + 1] > 0)
      groups.Start.push_back(start[c] + start[c + 1]);
    start[c + 1] += start[c];
  }
  if (count < minimumPerCell * static_cast<std::int64_t>(groups.Start.size() - 1))
    return false; // too few queries per cell to share a search
  groups.Order.resize(queries.size());
  for (std::int64_t i = 0; i < count; ++i)
    groups.Order[start[cellOf[i]]++] = static_cast<int>(i);
  return true;
}

void PointGrid::GroupCandidates(const std::vector<Eigen::Vector3d>& queries, const QueryGroups& groups,
  std::int64_t g, double radius, GroupSearch& search) const
{
  Eigen::Vector3d lower = queries[groups.Order[groups.Start[g]]], upper = lower;
  for (int i = groups.Start[g] + 1; i < groups.Start[g + 1]; ++i)
  {
    lower = lower.cwiseMin(queries[groups.Order[i]]);
    upper = upper.cwiseMax(queries[groups.Order[i]]);
  }
  // Every query of the box lies within h of its centre c. With a radius, a point farther than
  // radius + h from c is beyond it for all of them. Without one, the point nearest c is d from
  // c, so each query's nearest is at most d + h from it, and so at most d + 2h from c.
  const Eigen::Vector3d centre = 0.5 * (lower + upper);
  const double h = 0.5 * (upper - lower).norm();
  const double reach = std::isinf(radius) ? (this->Points[this->NearestAny(centre)] - centre).norm() + 2.0 * h
                                          : radius + h;
  const double scale = std::max({ centre.cwiseAbs().maxCoeff(), this->Origin.cwiseAbs().maxCoeff(), reach });
  this->PointsNear(centre, reach + 1e-9 * scale, search.Near);
  search.Centre = centre;
  search.Slack = 1e-9 * scale; // far beyond the rounding of these distances
  search.Candidates.clear();
  for (const int index : search.Near)
  {
    search.Candidates.push_back({ (this->Points[index] - centre).norm(), index, this->Points[index] });
  }
  std::sort(search.Candidates.begin(), search.Candidates.end());
}

std::vector<int> PointGrid::NearestAnyOfAll(const std::vector<Eigen::Vector3d>& queries, int threads) const
{
  return this->NearestOfAll(queries, std::numeric_limits<double>::infinity(),
    [](std::int64_t, int) { return true; }, threads);
}
} // namespace cbc3d
