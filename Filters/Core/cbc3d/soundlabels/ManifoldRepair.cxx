#include "cbc3d/soundlabels/ManifoldRepair.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/soundlabels/StarRepairer.h"

#include <deque>

namespace cbc3d
{
namespace
{

// Per vertex, whether every class is already manifold there: the first sweep's answers, found
// in parallel (each thread with its own star and scratch) before any label changes.
std::vector<char> ManifoldVertices(const StarRepairer& repairer, std::size_t pointCount, int threads)
{
  std::vector<char> manifold(pointCount, 0);
  const std::int64_t count = static_cast<std::int64_t>(pointCount);
  RegionErrors errors;
#pragma omp parallel num_threads(threads)
  {
    VertexStar star;
    std::vector<int> localOf;
    StarViolation violation;
    errors.Run([&] { localOf.assign(repairer.TetCount(), -1); }); // every thread meets the loop
#pragma omp for schedule(dynamic, 1024)
    for (std::int64_t p = 0; p < count; ++p)
    {
      if (errors.Failed())
        continue;
      if (repairer.IsUniform(p))
      {
        manifold[p] = 1;
        continue;
      }
      errors.Run([&] {
        repairer.Load(p, star, localOf);
        manifold[p] = !repairer.FindViolation(star, violation);
      });
    }
  }
  errors.Rethrow();
  return manifold;
}
} // namespace

ManifoldRepairResult RepairManifoldLabels(const std::vector<Eigen::Vector3d>& points,
  const std::vector<Tet>& tets, const std::vector<TetNeighbours>& across,
  std::int32_t background, const ClassVotes& votes, std::vector<std::int32_t>& classes,
  const std::vector<PointId>& seeds, int numberOfThreads, const std::vector<std::int32_t>& backgroundRegionOfTet)
{
  ManifoldRepairResult result;
  const std::size_t pointCount = points.size();
  StarRepairer repairer(points, tets, across, background, votes, classes, backgroundRegionOfTet, numberOfThreads);
  std::deque<PointId> queue;
  std::vector<char> queued(pointCount, 0);
  std::vector<int> visits(pointCount, 0);
  auto push = [&](PointId p) {
    if (!queued[p])
    {
      queued[p] = 1;
      queue.push_back(p);
    }
  };
  // A first sweep over every vertex skips those found manifold beforehand and untouched since:
  // looking again would find nothing to repair, so the result is the serial sweep's.
  std::vector<char> known;
  if (seeds.empty())
  {
    known = ManifoldVertices(repairer, pointCount, ThreadCount(numberOfThreads));
    for (std::size_t p = 0; p < pointCount; ++p)
      push(static_cast<PointId>(p));
  }
  for (const PointId p : seeds)
    push(p);
  // Every repair changes at least one tet; the bound keeps a pathological cycle finite.
  const std::int64_t budget = 64 * static_cast<std::int64_t>(pointCount) + 1024;
  std::vector<std::int64_t> changed;
  while (!queue.empty() && result.Repairs < budget)
  {
    const PointId v = queue.front();
    queue.pop_front();
    queued[v] = 0;
    if ((!known.empty() && known[v]) || repairer.IsUniform(v))
    {
      continue;
    }
    changed.clear();
    repairer.RepairStar(v, visits[v], changed, result);
    if (changed.empty())
    {
      continue;
    }
    ++visits[v];
    result.Relabelled += static_cast<std::int64_t>(changed.size());
    for (const std::int64_t t : changed)
      for (const PointId p : tets[t])
      {
        push(p);
        if (!known.empty())
          known[p] = 0; // its star changed
      }
  }
  // Each vertex left the queue manifold, and went back on it whenever its star changed.
  if (!queue.empty())
  {
    result.Unrepaired = CountNonManifoldVertices(points, tets, across, background, classes);
  }
  return result;
}

std::int64_t CountNonManifoldVertices(const std::vector<Eigen::Vector3d>& points,
  const std::vector<Tet>& tets, const std::vector<TetNeighbours>& across,
  std::int32_t background, const std::vector<std::int32_t>& classes)
{
  const ClassVotes none = [](std::int64_t, std::int32_t) { return std::int64_t(0); };
  std::vector<std::int32_t> copy(classes);
  const std::size_t pointCount = points.size();
  StarRepairer repairer(points, tets, across, background, none, copy);
  std::int64_t count = 0;
  VertexStar star;
  StarViolation violation;
  for (std::size_t p = 0; p < pointCount; ++p)
  {
    if (repairer.IsUniform(static_cast<PointId>(p)))
      continue;
    repairer.Load(static_cast<PointId>(p), star);
    count += repairer.FindViolation(star, violation);
  }
  return count;
}
} // namespace cbc3d
