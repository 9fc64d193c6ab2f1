#ifndef cbc3d_TetVoxelSampler_h
#define cbc3d_TetVoxelSampler_h

// Stage: sampling, the mesh against the voxels. Takes a label image and tets; gives each tet's
// voxel counts per label (this file), the tissues' face-connected components
// (TissueComponents.h), and the tissues' surface vertices and boundary voxels (SurfacePoints.h).
// Used by the lattice, the sound labels, refinement, quality and deformation.

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/UninitializedVector.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace cbc3d
{
/// Sample weights: a whole voxel weighs VoxelWeight; a sample of a sub-grid with s samples per
/// voxel along each axis weighs VoxelWeight / s^3 (s up to 16).
constexpr std::int64_t VoxelWeight = 16 * 16 * 16;

/// The tet owning each stored voxel's centre (indexed like LabelImage::Labels; -1 for none):
/// as large as the image's stored box, so it is filled in parallel (AssignInParallel).
using VoxelOwners = UninitializedVector<std::int32_t>;

/// How much of each label a tet holds, in sample weights.
struct LabelCounts
{
  std::vector<std::pair<std::int32_t, std::int64_t>> Counts; // (label, weight), small

  void Clear() { this->Counts.clear(); }
  void Add(std::int32_t label, std::int64_t weight = VoxelWeight);
  /// The weight of one label (0 if absent).
  std::int64_t Of(std::int32_t label) const;
  std::int64_t Total() const;
  /// Samples of labels that are tissues of the image.
  std::int64_t TissueTotal(const LabelImage& image) const;
  /// The most frequent tissue label (ties go to the smaller label); false when there is none.
  bool MajorityTissue(const LabelImage& image, std::int32_t& label) const;
  /// The most frequent label of all, background included; ties go to a tissue over
  /// background (a tet half in a narrow gap keeps the tissue around it), then to the smaller
  /// label. False when the tet holds no sample.
  bool Majority(const LabelImage& image, std::int32_t& label) const;
};

/// Counts the labels of the voxel centres inside a tet given by its world-space corners.
/// A point on the boundary of tets belongs to exactly one of them: the one that a fixed,
/// generic direction points into from it, so the tets of a conforming mesh share out the
/// voxels with none counted twice. A tet smaller than a voxel may hold no voxel centre: then
/// the tet's box is sampled on a finer grid, 2, 4, 8 and at most 16 samples per voxel along
/// each axis, each sample taking the label of the voxel it falls in (the paper's local
/// up-sampling) with a weight of its share of a voxel. Samples beyond the image count as the
/// first background label (as the image border counts as outside for boundary voxels).
/// With `voxelOwner` (indexed like image.Labels), each stored voxel whose centre the tet owns
/// gets `owner` written at its index.
/// Returns the sub-grid used: 1 when the tet holds voxel centres (its counts are then whole
/// voxels that no other tet counts), 2 to 16 otherwise, 0 when it holds no sample at all.
int SampleTetLabels(const LabelImage& image, const std::array<Eigen::Vector3d, 4>& corners,
  LabelCounts& counts, std::int32_t owner = -1, std::int32_t* voxelOwner = nullptr);
} // namespace cbc3d

#endif
