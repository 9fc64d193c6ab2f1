#include "cbc3d/base/PointTets.h"

#include "cbc3d/base/Parallel.h"

#include <algorithm>

namespace cbc3d
{
PointTets::PointTets(const std::vector<Tet>& tets, std::size_t pointCount, int threads)
  : Start(pointCount + 1, 0)
{
  CheckTetCount(tets.size());
  const int workers = ThreadCount(threads);
  const std::int64_t tetCount = static_cast<std::int64_t>(tets.size());
  std::int64_t* start = this->Start.data();
#pragma omp parallel for schedule(static) num_threads(workers)
  for (std::int64_t t = 0; t < tetCount; ++t)
    for (const PointId p : tets[t])
    {
#pragma omp atomic
      ++start[p + 1];
    }
  for (std::size_t p = 0; p < pointCount; ++p)
    this->Start[p + 1] += this->Start[p];
  this->Tets.resize(this->Start[pointCount]);
  std::vector<std::int64_t> fill(this->Start.begin(), this->Start.end() - 1);
  std::int64_t* next = fill.data();
  std::int32_t* around = this->Tets.data();
  // On threads the tets land in any order within a point's row: sorted after.
#pragma omp parallel for schedule(static) num_threads(workers)
  for (std::int64_t t = 0; t < tetCount; ++t)
    for (const PointId p : tets[t])
    {
      std::int64_t slot;
#pragma omp atomic capture
      slot = next[p]++;
      around[slot] = static_cast<std::int32_t>(t);
    }
  if (workers > 1)
  {
    const std::int64_t points = static_cast<std::int64_t>(pointCount);
#pragma omp parallel for schedule(dynamic, 4096) num_threads(workers)
    for (std::int64_t p = 0; p < points; ++p)
      std::sort(around + start[p], around + start[p + 1]);
  }
}
} // namespace cbc3d
