#ifndef cbc3d_ImageRegions_h
#define cbc3d_ImageRegions_h

#include "cbc3d/base/TetMesh.h"
#include "cbc3d/sampling/TetVoxelSampler.h"
#include "cbc3d/sampling/TissueComponents.h"

#include <cstdint>
#include <vector>

namespace cbc3d
{
/// The image's components as the mesh should keep them: regions 0..n-1 are the tissue
/// components, and the background's components (cavities) follow. A background component that
/// reaches the layer around the tissues is the outside, which the mesh's outside stands for.
/// Everything is read from runs, not from a whole-image copy.
struct ImageRegions
{
  const TissueComponents* Tissues = nullptr;
  BackgroundComponents Gaps;
  std::vector<std::int32_t> RegionOfGap; // per background component: its region, or -1 (not kept)
  std::vector<std::int32_t> ClassOfRegion;
  /// Per region: a speck (fewer voxels than a component must have to be kept for sure), which
  /// keeps its piece only where that piece lies against another tissue, not afloat.
  std::vector<char> Speck;

  /// Whether the image has a cavity to keep (a region of the background).
  bool HasCavity() const;
};

/// The regions of an image whose tissue components are `tissues` (which must outlive them):
/// every tissue component, and every cavity of at least `minimumVoxels` voxels, as class
/// `background`.
ImageRegions FindImageRegions(const LabelImage& image, const TissueComponents& tissues,
  int minimumVoxels, std::int32_t background);
/// The same from the background's components, found already (FindBackgroundComponents).
ImageRegions FindImageRegions(const TissueComponents& tissues, BackgroundComponents gaps, int minimumVoxels,
  std::int32_t background);

/// Per tet, the background component of the image that most of its background voxels belong to
/// (`voxelOwner`: the tet owning each voxel centre, or -1): a kept cavity's region,
/// OutsideRegion, or NoRegion (no background at all, or a cavity too small to keep). A tet that
/// owns no background voxel centre of the tissues' box (a tet smaller than a voxel, or one
/// beyond the box) is judged by the voxels under five points of it instead: its centroid and
/// the points halfway from there to each vertex. Empty where the image has no cavity to keep:
/// then every background tet is the outside.
constexpr std::int32_t NoRegion = -1;
constexpr std::int32_t OutsideRegion = -2;
std::vector<std::int32_t> BackgroundRegionOfTets(const LabelImage& image, const ImageRegions& regions,
  const VoxelOwners& voxelOwner, const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets,
  int numberOfThreads);
} // namespace cbc3d

#endif
