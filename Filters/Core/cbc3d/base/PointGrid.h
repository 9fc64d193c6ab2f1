#ifndef cbc3d_PointGrid_h
#define cbc3d_PointGrid_h

#include "cbc3d/base/Parallel.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace cbc3d
{
/// Points bucketed on a uniform grid over their bounding box, for nearest-point queries within
/// a radius. Holds a reference to the points: they must outlive the grid and stay in place
/// (a copy in cell order measured no faster, and held tens of MB on the heads).
class PointGrid
{
public:
  /// Buckets `points` on `threads` threads (0: all cores); the grid is the same for any number.
  PointGrid(const std::vector<Eigen::Vector3d>& points, double cell, int threads = 1);

  /// The nearest point within `radius` that `accept(index)` takes; -1 if none. Ties go to the
  /// lower index, so the answer does not depend on the order of the search. The search visits
  /// shells of cells outwards from x's cell and stops once no unvisited cell can hold a nearer
  /// point: a large radius costs little where a point is near.
  template <typename Accept>
  int Nearest(const Eigen::Vector3d& x, double radius, const Accept& accept) const;

  /// The nearest point within `radius`; -1 if none.
  int Nearest(const Eigen::Vector3d& x, double radius) const
  {
    return this->Nearest(x, radius, [](int) { return true; });
  }

  /// The nearest point at any distance; -1 only when the grid is empty.
  int NearestAny(const Eigen::Vector3d& x) const;

  /// Nearest(queries[q], radius, accept(q, index)) for each query, on `threads` threads (0: all
  /// cores): the same answers. Where the queries are much denser than the points (a tissue's
  /// boundary voxels against its surface vertices, the more so on fine images) they are taken
  /// cell by cell: the queries in one cell of this grid share one list of the points that can
  /// be the answer for any of them. An infinite radius is NearestAny's search.
  template <typename Accept>
  std::vector<int> NearestOfAll(
    const std::vector<Eigen::Vector3d>& queries, double radius, const Accept& accept, int threads) const;

  /// NearestAny of each of `queries`: NearestOfAll without a radius or a filter.
  std::vector<int> NearestAnyOfAll(const std::vector<Eigen::Vector3d>& queries, int threads) const;

private:
  // A query's best point so far and its squared distance.
  struct Best
  {
    int Index;
    double Distance;
  };

  // The cell of x along each axis, clamped to the grid (for bucketing the points).
  Eigen::Vector3i CellOf(const Eigen::Vector3d& x) const;

  // CellOf as an index into CellStart.
  std::int64_t CellIndex(const Eigen::Vector3d& x) const;

  // Every point within `radius` of x (a little more, never less), in no particular order.
  void PointsNear(const Eigen::Vector3d& x, double radius, std::vector<int>& found) const;

  // Queries in the order of this grid's cells: group g is Order[Start[g] .. Start[g + 1]).
  struct QueryGroups
  {
    std::vector<int> Order;
    std::vector<int> Start;
  };

  // Groups the queries by cell (finding their cells on `threads`); false (and no Order) where
  // there are fewer than `minimumPerCell` per cell on average, too few for a shared search to pay.
  bool GroupByCell(
    const std::vector<Eigen::Vector3d>& queries, int minimumPerCell, QueryGroups& groups, int threads) const;

  // The points that can answer a query of one group, nearest its centre first: a query e from
  // the centre is at least FromCentre - e from each, so its search ends at the first that is
  // farther than its best so far by that bound (less Slack, for rounding).
  struct Candidate
  {
    double FromCentre;
    int Index;
    Eigen::Vector3d Point;
    bool operator<(const Candidate& other) const
    {
      return this->FromCentre < other.FromCentre || (this->FromCentre == other.FromCentre && this->Index < other.Index);
    }
  };
  struct GroupSearch
  {
    Eigen::Vector3d Centre;
    double Slack;
    std::vector<int> Near;
    std::vector<Candidate> Candidates;
  };

  // The points that can answer a query of group g within `radius` (infinite: NearestAny).
  void GroupCandidates(const std::vector<Eigen::Vector3d>& queries, const QueryGroups& groups,
    std::int64_t g, double radius, GroupSearch& search) const;

  // NearestOfAll's answers for the queries of group g, from the group's shared list.
  template <typename Accept>
  void NearestOfGroup(const std::vector<Eigen::Vector3d>& queries, const QueryGroups& groups, std::int64_t g,
    double radius, const Accept& accept, GroupSearch& search, std::vector<int>& nearest) const;

  // The cell of x along each axis, not clamped: x lies inside it even when outside the grid.
  Eigen::Matrix<std::int64_t, 3, 1> QueryCellOf(const Eigen::Vector3d& x) const;

  // How far x is from every cell outside the cube of cells centre +- k that lies in the grid
  // (a lower bound, kept slightly low for rounding); infinite when the cube covers the grid.
  double OutsideDistance(const Eigen::Vector3d& x, const Eigen::Matrix<std::int64_t, 3, 1>& centre,
    std::int64_t k) const;

  // Offers the points of cells [x0, x1] of row (y, z) to `best`.
  template <typename Accept>
  void ScanRow(const Eigen::Vector3d& x, std::int64_t y, std::int64_t z, std::int64_t x0,
    std::int64_t x1, const Accept& accept, Best& best) const;

  // Offers the points of the cells at Chebyshev distance k from `centre` to `best`.
  template <typename Accept>
  void ScanShell(const Eigen::Vector3d& x, const Eigen::Matrix<std::int64_t, 3, 1>& centre,
    std::int64_t k, const Accept& accept, Best& best) const;

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
  if (this->Sorted.empty() || !(radius >= 0.0))
  {
    return -1;
  }
  // Exact: every point nearer than the best found, or as near with a lower index, lies in a
  // visited shell, since the unvisited cells are all farther than OutsideDistance.
  const Eigen::Matrix<std::int64_t, 3, 1> centre = this->QueryCellOf(x);
  std::int64_t first = 0; // shells nearer than this hold no cell of the grid
  for (int a = 0; a < 3; ++a)
  {
    first = std::max({ first, -centre[a], centre[a] - (this->Size[a] - 1) });
  }
  Best best{ -1, radius * radius };
  for (std::int64_t k = first;; ++k)
  {
    this->ScanShell(x, centre, k, accept, best);
    const double outside = this->OutsideDistance(x, centre, k);
    if (std::isinf(outside) || outside > radius || (best.Index >= 0 && best.Distance < outside * outside))
    {
      return best.Index;
    }
  }
}

template <typename Accept>
std::vector<int> PointGrid::NearestOfAll(
  const std::vector<Eigen::Vector3d>& queries, double radius, const Accept& accept, int threads) const
{
  const std::int64_t count = static_cast<std::int64_t>(queries.size());
  std::vector<int> nearest(queries.size(), -1);
  if (this->Sorted.empty() || count == 0 || !(radius >= 0.0))
    return nearest;
  // A radius of a few cells makes long shared lists, which pay only for dense queries (the
  // matcher's targets: 8 a cell on the brain, searched one by one, 0.77 against 1.13 G
  // instructions shared; 36 a cell on the brain at twice the resolution, 3.23 against 2.30 G).
  QueryGroups groups;
  // A group's lists grow, and `accept` may throw: errors leave the regions as one exception.
  RegionErrors errors;
  if (!this->GroupByCell(queries, std::isinf(radius) ? 4 : 16, groups, threads))
  {
#pragma omp parallel for schedule(dynamic, 256) num_threads(ThreadCount(threads))
    for (std::int64_t q = 0; q < count; ++q)
      errors.Run([&] { nearest[q] = this->Nearest(queries[q], radius, [&](int index) { return accept(q, index); }); });
    errors.Rethrow();
    return nearest;
  }
  const std::int64_t groupCount = static_cast<std::int64_t>(groups.Start.size()) - 1;
#pragma omp parallel num_threads(ThreadCount(threads))
  {
    GroupSearch search;
#pragma omp for schedule(dynamic, 16)
    for (std::int64_t g = 0; g < groupCount; ++g)
      errors.Run([&] { this->NearestOfGroup(queries, groups, g, radius, accept, search, nearest); });
  }
  errors.Rethrow();
  return nearest;
}

template <typename Accept>
void PointGrid::NearestOfGroup(const std::vector<Eigen::Vector3d>& queries, const QueryGroups& groups,
  std::int64_t g, double radius, const Accept& accept, GroupSearch& search, std::vector<int>& nearest) const
{
  this->GroupCandidates(queries, groups, g, radius, search);
  for (int i = groups.Start[g]; i < groups.Start[g + 1]; ++i)
  {
    // As ScanRow compares: the nearest accepted, the lower index on a tie.
    const std::int64_t q = groups.Order[i];
    const double fromCentre = (queries[q] - search.Centre).norm() + search.Slack;
    Best best{ -1, radius * radius };
    for (const Candidate& candidate : search.Candidates)
    {
      const double atLeast = candidate.FromCentre - fromCentre;
      if (atLeast > 0.0 && atLeast * atLeast > best.Distance)
        break; // this one and all after it are farther than the best
      const double distance = (candidate.Point - queries[q]).squaredNorm();
      const int index = candidate.Index;
      if ((distance < best.Distance || (distance == best.Distance && (best.Index < 0 || index < best.Index))) &&
        accept(q, index))
        best = Best{ index, distance };
    }
    nearest[q] = best.Index;
  }
}

template <typename Accept>
void PointGrid::ScanRow(const Eigen::Vector3d& x, std::int64_t y, std::int64_t z, std::int64_t x0,
  std::int64_t x1, const Accept& accept, Best& best) const
{
  const std::int64_t row = (z * this->Size[1] + y) * this->Size[0];
  for (int s = this->CellStart[row + x0]; s < this->CellStart[row + x1 + 1]; ++s)
  {
    const int index = this->Sorted[s];
    const double distance = (this->Points[index] - x).squaredNorm();
    if ((distance < best.Distance || (distance == best.Distance && (best.Index < 0 || index < best.Index))) &&
      accept(index))
    {
      best = Best{ index, distance };
    }
  }
}

template <typename Accept>
void PointGrid::ScanShell(const Eigen::Vector3d& x, const Eigen::Matrix<std::int64_t, 3, 1>& centre,
  std::int64_t k, const Accept& accept, Best& best) const
{
  Eigen::Matrix<std::int64_t, 3, 1> lo, hi;
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = std::max<std::int64_t>(centre[a] - k, 0);
    hi[a] = std::min<std::int64_t>(centre[a] + k, this->Size[a] - 1);
    if (lo[a] > hi[a])
    {
      return; // the shell misses the grid
    }
  }
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
    {
      if (std::abs(z - centre[2]) == k || std::abs(y - centre[1]) == k)
      {
        this->ScanRow(x, y, z, lo[0], hi[0], accept, best); // a face of the shell: the whole row
        continue;
      }
      for (const std::int64_t end : { centre[0] - k, centre[0] + k }) // inside the faces: the ends
      {
        if (end >= lo[0] && end <= hi[0])
        {
          this->ScanRow(x, y, z, end, end, accept, best);
        }
      }
    }
}
} // namespace cbc3d

#endif
