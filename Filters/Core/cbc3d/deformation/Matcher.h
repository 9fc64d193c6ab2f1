#ifndef cbc3d_Matcher_h
#define cbc3d_Matcher_h

#include "cbc3d/base/PointGrid.h"
#include "cbc3d/deformation/BoundaryTargets.h"
#include "cbc3d/deformation/SurfaceSources.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace cbc3d
{
/// The registration's correspondences: each source's goal, from the targets whose label-sets
/// it accepts.
class Matcher
{
public:
  Matcher(const SurfaceSources& sources, const std::vector<BoundaryTarget>& targets, int threads);

  /// Goals for the sources at positions x: each source's nearest target of an accepted
  /// label-set within twice its element size, averaged with the targets whose nearest source
  /// it is (so that parts of the image boundary far from every vertex pull the surface too).
  /// Sources with neither are not `matched`.
  void Match(const std::vector<Eigen::Vector3d>& x, std::vector<Eigen::Vector3d>& goals,
    std::vector<char>& matched) const;

private:
  bool Accepts(std::int64_t source, std::int64_t target) const;

  const SurfaceSources& SourceList;
  int Threads;
  std::vector<Eigen::Vector3d> TargetPoints;
  std::vector<int> TargetSet;             // per target, the number of its label-set
  std::vector<std::vector<int>> Accepted; // per source, the label-set numbers it accepts
  double LargestSize = 0.0;               // the largest element size at a source
  double Cell = 0.0;                      // grid cell: twice that
  std::unique_ptr<PointGrid> TargetGrid;
};
} // namespace cbc3d

#endif
