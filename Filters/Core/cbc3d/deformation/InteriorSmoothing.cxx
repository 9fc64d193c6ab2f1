#include "cbc3d/deformation/InteriorSmoothing.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/TetGeometry.h"

#include <algorithm>

namespace cbc3d
{
InteriorSmoothing::InteriorSmoothing(const std::vector<Tet>& tets, std::size_t pointCount,
  const std::vector<double>* edgeLimits, int threads)
  : Tets(tets)
  , EdgeLimits(edgeLimits)
  , Around(tets, pointCount, threads)
{
}

bool InteriorSmoothing::WithinEdgeLimits(PointId p, const std::vector<Eigen::Vector3d>& x) const
{
  for (std::int64_t i = this->Around.Start[p]; i < this->Around.Start[p + 1]; ++i)
  {
    const std::int64_t t = this->Around.Tets[i];
    const double limit = (*this->EdgeLimits)[t];
    if (limit > 0.0 && LongestEdgeOf(x, this->Tets[t]) > limit)
      return false;
  }
  return true;
}

namespace
{
// How bad a tet is: its largest dihedral |cos|, 2 when it is inverted or flat.
double Badness(const std::vector<Eigen::Vector3d>& x, const Tet& t)
{
  return SignedVolume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]) > 0.0
    ? LargestDihedralCosine(x[t[0]], x[t[1]], x[t[2]], x[t[3]])
    : 2.0;
}
} // namespace

std::vector<char> InteriorSmoothing::SharingATetWith(const std::vector<char>& marked, int threads) const
{
  const std::int64_t count = static_cast<std::int64_t>(this->Around.Start.size()) - 1;
  std::vector<char> sharing(count, 0);
#pragma omp parallel for schedule(dynamic, 4096) num_threads(ThreadCount(threads))
  for (std::int64_t p = 0; p < count; ++p)
  {
    for (std::int64_t i = this->Around.Start[p]; i < this->Around.Start[p + 1] && !sharing[p]; ++i)
    {
      const Tet& tet = this->Tets[this->Around.Tets[i]];
      sharing[p] = marked[tet[0]] || marked[tet[1]] || marked[tet[2]] || marked[tet[3]];
    }
  }
  return sharing;
}

std::vector<std::vector<PointId>> InteriorSmoothing::Levels(const std::vector<char>& movable) const
{
  // A movable point's level is one more than its movable neighbours' before it in point order:
  // neighbours (they share a tet) are in different levels, the earlier one first.
  const std::size_t count = this->Around.Start.size() - 1;
  std::vector<int> level(count, -1);
  std::vector<std::vector<PointId>> levels;
  for (std::size_t p = 0; p < count; ++p)
  {
    if (!movable[p] || this->Around.Start[p] == this->Around.Start[p + 1])
      continue;
    int at = 0;
    for (std::int64_t i = this->Around.Start[p]; i < this->Around.Start[p + 1]; ++i)
      for (const PointId q : this->Tets[this->Around.Tets[i]])
        if (q < static_cast<PointId>(p) && level[q] >= at)
          at = level[q] + 1;
    level[p] = at;
    if (at == static_cast<int>(levels.size()))
      levels.emplace_back();
    levels[at].push_back(static_cast<PointId>(p));
  }
  return levels;
}

bool InteriorSmoothing::TryMove(
  PointId p, std::vector<Eigen::Vector3d>& x, std::vector<double>& badness, std::vector<double>& trial) const
{
  const std::int64_t begin = this->Around.Start[p], end = this->Around.Start[p + 1];
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (std::int64_t i = begin; i < end; ++i)
    for (const PointId q : this->Tets[this->Around.Tets[i]])
      centre += x[q];
  centre /= 4.0 * double(end - begin);
  double before = 0.0;
  for (std::int64_t i = begin; i < end; ++i)
    before = std::max(before, badness[this->Around.Tets[i]]);
  const Eigen::Vector3d kept = x[p];
  x[p] = centre;
  trial.clear();
  for (std::int64_t i = begin; i < end && (trial.empty() || trial.back() < before); ++i)
    trial.push_back(Badness(x, this->Tets[this->Around.Tets[i]]));
  if (trial.size() == std::size_t(end - begin) && trial.back() < before &&
    (!this->EdgeLimits || this->WithinEdgeLimits(p, x)))
  {
    for (std::int64_t i = begin; i < end; ++i)
      badness[this->Around.Tets[i]] = trial[i - begin];
    return true;
  }
  x[p] = kept;
  return false;
}

std::size_t InteriorSmoothing::Smooth(
  std::vector<Eigen::Vector3d>& x, const std::vector<char>& movable, int sweeps, int threads) const
{
  // Each tet's badness at the current positions, kept as its vertices move: a vertex's worst
  // before a move is read, not measured again, and a move is given up at the first tet that
  // would be no better than that worst. The same values as measuring everything each time,
  // so the same moves. A tet is first read either before any of its vertices moved or after a
  // move stored its value, so the tets around movable points are all measured at the start,
  // on the threads.
  const std::int64_t tetCount = static_cast<std::int64_t>(this->Tets.size());
  std::vector<double> badness(tetCount, -1.0); // -1: not around a movable point
#pragma omp parallel for schedule(static) num_threads(ThreadCount(threads))
  for (std::int64_t t = 0; t < tetCount; ++t)
  {
    const Tet& tet = this->Tets[t];
    if (movable[tet[0]] || movable[tet[1]] || movable[tet[2]] || movable[tet[3]])
    {
      badness[t] = Badness(x, tet);
    }
  }
  const std::vector<std::vector<PointId>> levels = this->Levels(movable);
  std::size_t moves = 0;
  for (int sweep = 0; sweep < sweeps; ++sweep)
  {
    std::size_t moved = 0;
    RegionErrors errors; // out of memory in a thread: thrown again below, not std::terminate
#pragma omp parallel num_threads(ThreadCount(threads)) reduction(+ : moved)
    {
      std::vector<double> trial;
      for (const std::vector<PointId>& level : levels)
      {
        const std::int64_t count = static_cast<std::int64_t>(level.size());
#pragma omp for schedule(static)
        for (std::int64_t i = 0; i < count; ++i)
          errors.Run([&] { moved += this->TryMove(level[i], x, badness, trial); });
      }
    }
    errors.Rethrow();
    moves += moved;
    if (moved == 0)
    {
      break;
    }
  }
  return moves;
}
} // namespace cbc3d
