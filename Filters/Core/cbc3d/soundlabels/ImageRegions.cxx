#include "cbc3d/soundlabels/ImageRegions.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/TetGeometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <utility>

namespace cbc3d
{
bool ImageRegions::HasCavity() const
{
  return std::any_of(this->RegionOfGap.begin(), this->RegionOfGap.end(), [](std::int32_t r) { return r >= 0; });
}

ImageRegions FindImageRegions(const LabelImage& image, const TissueComponents& tissues,
  int minimumVoxels, std::int32_t background)
{
  return FindImageRegions(tissues, FindBackgroundComponents(image), minimumVoxels, background);
}

ImageRegions FindImageRegions(const TissueComponents& tissues, BackgroundComponents gaps, int minimumVoxels,
  std::int32_t background)
{
  ImageRegions regions;
  regions.Tissues = &tissues;
  regions.Gaps = std::move(gaps);
  const std::int32_t tissueCount = static_cast<std::int32_t>(tissues.Label.size());
  for (std::int32_t c = 0; c < tissueCount; ++c)
  {
    regions.ClassOfRegion.push_back(tissues.Label[c]);
    regions.Speck.push_back(tissues.Size[c] < minimumVoxels);
  }
  // Every background component has a region (unused where it is not kept).
  const BackgroundComponents& kept = regions.Gaps;
  for (std::size_t c = 0; c < kept.Size.size(); ++c)
  {
    const bool isKept = !kept.TouchesBorder[c] && kept.Size[c] >= minimumVoxels;
    regions.RegionOfGap.push_back(isKept ? tissueCount + std::int32_t(c) : -1);
    regions.ClassOfRegion.push_back(background);
    regions.Speck.push_back(0);
  }
  return regions;
}

namespace
{
// The region a background voxel of the image stands for: its component's, or the outside's
// beyond the tissues' box (which the components do not cover); NoRegion for a tissue voxel or
// a cavity too small to keep.
std::int32_t RegionOfVoxel(const LabelImage& image, const ImageRegions& regions, const std::array<int, 3>& at)
{
  if (!image.IsBackground(image.LabelOf(at[0], at[1], at[2])))
    return NoRegion;
  if (!image.IsStored(at[0], at[1], at[2]))
    return OutsideRegion;
  const std::int32_t gap = regions.Gaps.ComponentOf(image.VoxelIndex(at[0], at[1], at[2]));
  if (gap < 0 || regions.Gaps.TouchesBorder[gap])
    return OutsideRegion;
  return regions.RegionOfGap[gap];
}

// The region most of five points of a tet lie in (its centroid and halfway to each vertex).
std::int32_t SampledRegion(const LabelImage& image, const ImageRegions& regions, const std::vector<Eigen::Vector3d>& points,
  const Tet& tet)
{
  const Eigen::Vector3d centroid = Centroid(points[tet[0]], points[tet[1]], points[tet[2]], points[tet[3]]);
  std::array<std::int32_t, 5> found;
  for (int s = 0; s < 5; ++s)
  {
    const Eigen::Vector3d at = image.WorldToIndex(s == 0 ? centroid : 0.5 * (centroid + points[tet[s - 1]]));
    const std::array<int, 3> voxel = { int(std::lround(at[0])), int(std::lround(at[1])), int(std::lround(at[2])) };
    found[s] = RegionOfVoxel(image, regions, voxel);
  }
  std::int32_t best = NoRegion;
  int most = 0;
  for (const std::int32_t region : found)
  {
    const int count = region == NoRegion ? 0 : int(std::count(found.begin(), found.end(), region));
    if (count > most || (count == most && count > 0 && region < best))
    {
      most = count;
      best = region;
    }
  }
  return best;
}
} // namespace

std::vector<std::int32_t> BackgroundRegionOfTets(const LabelImage& image, const ImageRegions& regions,
  const VoxelOwners& voxelOwner, const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets,
  int numberOfThreads)
{
  const std::size_t tetCount = tets.size();
  if (!regions.HasCavity())
  {
    return {};
  }
  // Voxels per (tet, region), counted by stretches of one owner along a run.
  std::unordered_map<std::uint64_t, std::int64_t> held;
  std::vector<char> ownsBackground(tetCount, 0);
  auto key = [](std::int32_t tet, std::int32_t region) {
    return (std::uint64_t(std::uint32_t(tet)) << 32) | std::uint32_t(region - OutsideRegion);
  };
  for (const RunComponents::Run& run : regions.Gaps.Runs)
  {
    const std::int32_t region =
      regions.Gaps.TouchesBorder[run.Component] ? OutsideRegion : regions.RegionOfGap[run.Component];
    for (std::int64_t v = run.First; v <= run.Last;)
    {
      const std::int32_t owner = voxelOwner[v];
      std::int64_t end = v + 1;
      while (end <= run.Last && voxelOwner[end] == owner)
        ++end;
      if (owner >= 0)
        ownsBackground[owner] = 1;
      if (owner >= 0 && region != NoRegion)
        held[key(owner, region)] += end - v;
      v = end;
    }
  }
  std::vector<std::int32_t> regionOfTet(tetCount, NoRegion);
  std::vector<std::int64_t> most(tetCount, 0);
  for (const auto& [k, count] : held)
  {
    const std::size_t tet = k >> 32;
    const std::int32_t region = std::int32_t(k & 0xffffffffu) + OutsideRegion;
    // Ties go to the smaller region, so the answer does not depend on the map's order.
    if (count > most[tet] || (count == most[tet] && region < regionOfTet[tet]))
    {
      most[tet] = count;
      regionOfTet[tet] = region;
    }
  }
  const std::int64_t count = static_cast<std::int64_t>(tetCount);
#pragma omp parallel for schedule(dynamic, 1024) num_threads(ThreadCount(numberOfThreads))
  for (std::int64_t t = 0; t < count; ++t)
  {
    if (!ownsBackground[t])
      regionOfTet[t] = SampledRegion(image, regions, points, tets[t]);
  }
  return regionOfTet;
}
} // namespace cbc3d
