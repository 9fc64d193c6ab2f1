#include "cbc3d/deformation/GuardedStep.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/TetGeometry.h"
#include "cbc3d/deformation/VolumeAims.h"

#include <cmath>
#include <map>
#include <utility>

namespace cbc3d
{
double SmallestAngleMargin(const TetMesh& mesh, int threads)
{
  const std::int64_t count = static_cast<std::int64_t>(mesh.Tets.size());
  double smallest = M_PI;
#pragma omp parallel for schedule(static) reduction(min : smallest) num_threads(ThreadCount(threads))
  for (std::int64_t t = 0; t < count; ++t)
  {
    const Tet& tet = mesh.Tets[t];
    for (const double a : DihedralAngles(mesh.Points[tet[0]], mesh.Points[tet[1]], mesh.Points[tet[2]], mesh.Points[tet[3]]))
      smallest = std::min({ smallest, a, M_PI - a });
  }
  return smallest;
}

StepBounds MakeStepBounds(const TetMesh& mesh, double minimumRadians, const EdgeLengthLimits& limits)
{
  StepBounds bounds;
  bounds.MinimumRadians = minimumRadians;
  if (!limits.Any())
  {
    return bounds;
  }
  bounds.EdgeLimits.assign(mesh.Tets.size(), 0.0);
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const double limit = limits.Of(mesh.Labels[t]);
    if (limit > 0.0)
      bounds.EdgeLimits[t] = std::max(limit, LongestEdgeOf(mesh.Points, mesh.Tets[t]));
  }
  return bounds;
}

std::vector<std::int64_t> BadTets(const TetMesh& mesh, const std::vector<Eigen::Vector3d>& x,
  const StepBounds& bounds, int threads, const std::vector<char>* moved)
{
  const double minimumRadians = bounds.MinimumRadians;
  const bool edgeLimits = !bounds.EdgeLimits.empty();
  const std::int64_t count = static_cast<std::int64_t>(mesh.Tets.size());
  std::vector<char> bad(count, 0);
  const double largestCosine = std::cos(minimumRadians); // DihedralAnglesWithin's test, its cosine once
  // Dynamic: the tets around the moved points cluster, and a static half may hold them all.
#pragma omp parallel for schedule(dynamic, 1024) num_threads(ThreadCount(threads))
  for (std::int64_t t = 0; t < count; ++t)
  {
    const Tet& tet = mesh.Tets[t];
    if (moved && !((*moved)[tet[0]] || (*moved)[tet[1]] || (*moved)[tet[2]] || (*moved)[tet[3]]))
    {
      continue;
    }
    if (!(SignedVolume(x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]]) > 0.0))
    {
      bad[t] = 1;
      continue;
    }
    bad[t] = !(LargestDihedralCosine(x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]]) <= largestCosine) ||
      (edgeLimits && bounds.EdgeLimits[t] > 0.0 && LongestEdgeOf(x, tet) > bounds.EdgeLimits[t]);
  }
  std::vector<std::int64_t> result;
  for (std::int64_t t = 0; t < count; ++t)
  {
    if (bad[t])
    {
      result.push_back(t);
    }
  }
  return result;
}

StepOutcome GuardedStep(const TetMesh& mesh, const std::vector<Eigen::Vector3d>& x,
  const std::function<Eigen::Vector3d(std::size_t)>& step, const StepBounds& bounds, int threads,
  FidelityGuard& fidelity, const std::function<bool()>& keepGoing,
  std::vector<Eigen::Vector3d>& trial, std::vector<double>& share)
{
  trial.resize(x.size());
  share.assign(x.size(), 1.0);
  std::vector<char> moved(x.size()), spoilt(x.size(), 0);
  for (int round = 0; round < 50; ++round)
  {
    if (!keepGoing())
    {
      return StepOutcome::Aborted;
    }
    // Only tets with a point that moved since the last check, or that were spoilt then, can
    // have changed: the rest satisfied the bound when checked.
    const std::int64_t pointCount = static_cast<std::int64_t>(x.size());
#pragma omp parallel for schedule(static) num_threads(ThreadCount(threads))
    for (std::int64_t p = 0; p < pointCount; ++p)
    {
      const Eigen::Vector3d next = x[p] + share[p] * step(p);
      moved[p] = spoilt[p] || next != (round == 0 ? x[p] : trial[p]);
      trial[p] = next;
    }
    const std::vector<std::int64_t> bad = BadTets(mesh, trial, bounds, threads, &moved);
    if (bad.empty())
    {
      if (fidelity.Hold(trial, share, keepGoing) == 0)
      {
        return keepGoing() ? StepOutcome::Made : StepOutcome::Aborted;
      }
      std::fill(spoilt.begin(), spoilt.end(), 0);
      continue; // held for fidelity: try again with those vertices in place
    }
    // Once per round for each vertex, however many spoilt tets it has.
    std::fill(spoilt.begin(), spoilt.end(), 0);
    for (const std::int64_t t : bad)
    {
      for (const PointId p : mesh.Tets[t])
      {
        spoilt[p] = 1;
      }
    }
    for (std::size_t p = 0; p < x.size(); ++p)
    {
      if (spoilt[p])
      {
        share[p] = share[p] > 1.0 / 16.0 ? 0.5 * share[p] : 0.0;
      }
    }
  }
  return StepOutcome::Spoilt;
}

namespace
{
// A tissue within this of its target volume (relative) is done.
constexpr double VolumeTolerance = 1e-3;
} // namespace

StepOutcome RestoreTissueVolumes(const TissueVolumeKeeper& volumes, const TetMesh& mesh,
  const std::vector<PointId>& surface, std::vector<Eigen::Vector3d>& x, const StepBounds& bounds, int threads,
  FidelityGuard& fidelity, const std::function<bool()>& keepGoing)
{
  std::map<std::int32_t, double> now = volumes.Volumes(x); // measured once a round
  if (volumes.LargestRelativeShortfall(now) <= VolumeTolerance)
  {
    return StepOutcome::Made;
  }
  std::vector<char> moving(x.size(), 0);
  for (const PointId p : surface)
  {
    moving[p] = 1;
  }
  const TissueVolumeKeeper::AreaSums sums(volumes, moving);
  VolumeAims aims(volumes.TargetVolumes());
  std::vector<Eigen::Vector3d> trial;
  std::vector<double> share;
  // Each round's step is shortened where tets would spoil, so a few rounds may be needed.
  for (int round = 0; round < 8 && volumes.LargestRelativeShortfall(now) > VolumeTolerance; ++round)
  {
    const std::map<std::int32_t, double> aimed = aims.Aims(now);
    std::vector<Eigen::Vector3d> goals = x;
    volumes.OffsetGoals(goals, sums, now, aimed, threads);
    const StepOutcome outcome = GuardedStep(mesh, x, [&](std::size_t p) { return Eigen::Vector3d(goals[p] - x[p]); },
      bounds, threads, fidelity, keepGoing, trial, share);
    if (outcome != StepOutcome::Made)
    {
      return outcome;
    }
    x.swap(trial);
    fidelity.Accept(x, keepGoing);
    std::map<std::int32_t, double> after = volumes.Volumes(x);
    aims.Observe(now, aimed, after);
    now = std::move(after);
  }
  return StepOutcome::Made;
}
} // namespace cbc3d
