#ifndef cbc3d_SurfaceDistance_h
#define cbc3d_SurfaceDistance_h

#include <vector>

namespace cbc3d
{
/// Figures of the distances between two point sets A (mesh surface) and B (image boundary),
/// from the directed nearest-point distances of every point of A to B and of B to A.
struct SurfaceDistanceSummary
{
  double Hausdorff = 0.0;    // max(AToB, BToA): the two-sided Hausdorff distance
  double AToB = 0.0;         // largest distance from a point of A to B
  double BToA = 0.0;         // largest distance from a point of B to A
  double Percentile95 = 0.0; // max of the two directed 95th percentiles (nearest rank)
  double Mean = 0.0;         // mean of all directed distances of both sets
};

/// Summarizes directed distances; both lists must be non-empty. Reorders their contents.
SurfaceDistanceSummary SummarizeSurfaceDistances(std::vector<double>& aToB,
  std::vector<double>& bToA);

/// The summary of several pairs' distances as one sample, each directed list joined (the whole
/// mesh's, from its tissues'): a pair with few points weighs as little as it holds. Every
/// joined list must be non-empty.
SurfaceDistanceSummary SummarizeSurfaceDistancesTogether(const std::vector<const std::vector<double>*>& aToB,
  const std::vector<const std::vector<double>*>& bToA);
} // namespace cbc3d

#endif
