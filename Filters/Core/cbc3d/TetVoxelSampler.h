#ifndef cbc3d_TetVoxelSampler_h
#define cbc3d_TetVoxelSampler_h

#include "cbc3d/LabelImage.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace cbc3d
{
/// How many samples of each label a tet holds.
struct LabelCounts
{
  std::vector<std::pair<std::int32_t, std::int64_t>> Counts; // (label, samples), small

  void Clear() { this->Counts.clear(); }
  void Add(std::int32_t label);
  std::int64_t Total() const;
  /// Samples of labels that are tissues of the image.
  std::int64_t TissueTotal(const LabelImage& image) const;
  /// The most frequent tissue label (ties go to the smaller label); false when there is none.
  bool MajorityTissue(const LabelImage& image, std::int32_t& label) const;
};

/// Counts the labels of the voxel centres inside a tet given by its world-space corners
/// (points on the tet's faces count). A tet smaller than a voxel may hold no voxel centre:
/// then the tet's box is sampled on a finer grid, 2, 4, 8 and at most 16 samples per voxel
/// along each axis, each sample taking the label of the voxel it falls in (the paper's
/// local up-sampling). Samples outside the image are ignored.
void SampleTetLabels(const LabelImage& image, const std::array<Eigen::Vector3d, 4>& corners,
  LabelCounts& counts);
} // namespace cbc3d

#endif
