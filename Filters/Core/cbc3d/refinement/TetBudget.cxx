#include "cbc3d/refinement/TetBudget.h"

#include "cbc3d/refinement/EdgeLimits.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cbc3d
{
namespace
{
// Steps of the search for the largest set of splits that fits, the first of them by
// interpolation.
constexpr int SearchSteps = 12;
constexpr int InterpolationSteps = 3;
// A set of splits within this share of the tets allowed is as good as the best.
constexpr double CloseEnough = 0.01;

// The marked leaves, best first: those marked for an edge limit, then by the sample weight
// their tets hold of labels other than their own (the fidelity a split may win back); ties go
// to the lower index, so the order is the same on any thread count.
std::vector<std::size_t> LeavesBestFirst(const LabelledMesh& mesh, const std::vector<char>& marked)
{
  std::vector<double> gain(marked.size(), 0.0);
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const auto red = static_cast<std::size_t>(mesh.Source[t]);
    if (!marked[red])
      continue;
    for (const auto& [label, weight] : mesh.Counts[t].Counts)
    {
      if (label != mesh.Labels[t])
        gain[red] += double(weight);
    }
  }
  std::vector<std::size_t> leaves;
  for (std::size_t red = 0; red < marked.size(); ++red)
  {
    if (!marked[red])
      continue;
    if (marked[red] == MarkedForEdgeLimit)
      gain[red] = std::numeric_limits<double>::infinity();
    leaves.push_back(red);
  }
  std::stable_sort(leaves.begin(), leaves.end(), [&](std::size_t a, std::size_t b) { return gain[a] > gain[b]; });
  return leaves;
}

// The conforming tets after splitting the first `kept` leaves and bisecting the first
// `bisected` edges, on a copy of the hierarchy.
std::int64_t TetsAfter(const RedGreenMesh& hierarchy, const std::vector<std::size_t>& leaves, std::size_t kept,
  const std::vector<std::pair<PointId, PointId>>& bisect, std::size_t bisected, int threads)
{
  RedGreenMesh trial = hierarchy;
  for (std::size_t i = 0; i < kept; ++i)
    trial.SplitRed(leaves[i]);
  for (std::size_t i = 0; i < bisected; ++i)
    trial.SplitEdge(bisect[i].first, bisect[i].second);
  trial.Close();
  std::vector<Tet> tets;
  std::vector<std::int64_t> source;
  trial.BuildConforming(tets, source, nullptr, nullptr, threads);
  return static_cast<std::int64_t>(tets.size());
}
} // namespace

std::size_t TetBudget::Keep(const LabelImage& image, const LabelledMesh& mesh, const RedGreenMesh& hierarchy,
  std::vector<char>& marked, std::vector<std::pair<PointId, PointId>>& bisect, int threads, bool& fits) const
{
  // The new tets are tissue tets in the share the marked leaves' tets are now (splits gather
  // round the tissues' boundaries, where the share differs from the mesh's as a whole).
  std::int64_t tissueNow = 0, markedTets = 0, markedTissue = 0;
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const bool tissue = IsTissueLabel(image, mesh.Labels[t]);
    tissueNow += tissue;
    if (marked[static_cast<std::size_t>(mesh.Source[t])])
    {
      ++markedTets;
      markedTissue += tissue;
    }
  }
  const double newShare = markedTets > 0 ? std::max(0.05, double(markedTissue) / double(markedTets)) : 1.0;
  const double now = double(mesh.Tets.size());
  const double allowed = now + double(this->Target - tissueNow) / newShare;
  if (allowed - now < CloseEnough * allowed)
  {
    // Not even a few more tets fit: the budget is spent.
    fits = false;
    std::fill(marked.begin(), marked.end(), 0);
    bisect.clear();
    return 0;
  }
  std::vector<std::size_t> leaves = LeavesBestFirst(mesh, marked);
  const auto bisectedWith = [&](std::size_t kept) {
    return leaves.empty() ? bisect.size() : bisect.size() * kept / leaves.size();
  };
  const auto tetsWith = [&](std::size_t kept) {
    return double(TetsAfter(hierarchy, leaves, kept, bisect, bisectedWith(kept), threads));
  };
  // The largest count that fits, between `low` (fits) and `high` (does not); a count within
  // CloseEnough of the allowed tets ends the search.
  std::size_t low = 0, high = leaves.size();
  double lowTets = now, highTets = tetsWith(high);
  if (highTets <= allowed)
    low = high;
  for (int step = 0; step < SearchSteps && high - low > 1 && low != leaves.size() &&
       lowTets < (1.0 - CloseEnough) * allowed;
       ++step)
  {
    // Interpolation first; halving once it has failed to find any set that fits (the cost of
    // the first leaves, the best, may be far from the average).
    const double share = low == 0 && step >= InterpolationSteps ? 0.5
                                                                : (allowed - lowTets) / std::max(1.0, highTets - lowTets);
    const std::size_t middle = std::clamp<std::size_t>(low + std::size_t(share * double(high - low)), low + 1, high - 1);
    const double middleTets = tetsWith(middle);
    if (middleTets <= allowed)
    {
      low = middle;
      lowTets = middleTets;
    }
    else
    {
      high = middle;
      highTets = middleTets;
    }
  }
  fits = low > 0 || (leaves.empty() && !bisect.empty() && highTets <= allowed);
  for (std::size_t i = low; i < leaves.size(); ++i)
    marked[leaves[i]] = 0;
  bisect.resize(fits ? bisectedWith(low) : 0);
  return low;
}
} // namespace cbc3d
