#include "cbc3d/quality/SurfaceDistance.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace cbc3d
{
namespace
{
// The nearest-rank percentile: the smallest value with at least `fraction` of values <= it.
double Percentile(std::vector<double>& values, double fraction)
{
  const std::size_t rank =
    static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(values.size())));
  const auto nth = values.begin() + (std::max<std::size_t>(rank, 1) - 1);
  std::nth_element(values.begin(), nth, values.end());
  return *nth;
}
} // namespace

SurfaceDistanceSummary SummarizeSurfaceDistances(std::vector<double>& aToB,
  std::vector<double>& bToA)
{
  SurfaceDistanceSummary summary;
  summary.AToB = *std::max_element(aToB.begin(), aToB.end());
  summary.BToA = *std::max_element(bToA.begin(), bToA.end());
  summary.Hausdorff = std::max(summary.AToB, summary.BToA);
  // Sums in a fixed order, so the mean is the same for any thread count upstream.
  const double total = std::accumulate(aToB.begin(), aToB.end(), 0.0) +
    std::accumulate(bToA.begin(), bToA.end(), 0.0);
  summary.Mean = total / static_cast<double>(aToB.size() + bToA.size());
  summary.Percentile95 = std::max(Percentile(aToB, 0.95), Percentile(bToA, 0.95));
  return summary;
}

SurfaceDistanceSummary SummarizeSurfaceDistancesTogether(const std::vector<const std::vector<double>*>& aToB,
  const std::vector<const std::vector<double>*>& bToA)
{
  const auto join = [](const std::vector<const std::vector<double>*>& lists) {
    std::vector<double> joined;
    for (const std::vector<double>* list : lists)
      joined.insert(joined.end(), list->begin(), list->end());
    return joined;
  };
  std::vector<double> a = join(aToB), b = join(bToA);
  return SummarizeSurfaceDistances(a, b);
}
} // namespace cbc3d
