#include "cbc3d/ImageRegions.h"

#include <algorithm>
#include <unordered_map>

namespace cbc3d
{
bool ImageRegions::HasCavity() const
{
  return std::any_of(this->RegionOfGap.begin(), this->RegionOfGap.end(), [](std::int32_t r) { return r >= 0; });
}

ImageRegions FindImageRegions(const LabelImage& image, const TissueComponents& tissues,
  int minimumVoxels, std::int32_t background)
{
  ImageRegions regions;
  regions.Tissues = &tissues;
  regions.Gaps = FindBackgroundComponents(image);
  const std::int32_t tissueCount = static_cast<std::int32_t>(tissues.Label.size());
  for (std::int32_t c = 0; c < tissueCount; ++c)
  {
    regions.ClassOfRegion.push_back(tissues.Label[c]);
    regions.Speck.push_back(tissues.Size[c] < minimumVoxels);
  }
  // Every background component has a region (unused where it is not kept).
  const BackgroundComponents& gaps = regions.Gaps;
  for (std::size_t c = 0; c < gaps.Size.size(); ++c)
  {
    const bool kept = !gaps.TouchesBorder[c] && gaps.Size[c] >= minimumVoxels;
    regions.RegionOfGap.push_back(kept ? tissueCount + std::int32_t(c) : -1);
    regions.ClassOfRegion.push_back(background);
    regions.Speck.push_back(0);
  }
  return regions;
}

std::vector<std::int32_t> BackgroundRegionOfTets(
  const ImageRegions& regions, const VoxelOwners& voxelOwner, std::size_t tetCount)
{
  if (!regions.HasCavity())
  {
    return {};
  }
  // Voxels per (tet, region), counted by stretches of one owner along a run.
  std::unordered_map<std::uint64_t, std::int64_t> held;
  auto key = [](std::int32_t tet, std::int32_t region) {
    return (std::uint64_t(std::uint32_t(tet)) << 32) | std::uint32_t(region - OutsideRegion);
  };
  for (const RunComponents::Run& run : regions.Gaps.Runs)
  {
    const std::int32_t region =
      regions.Gaps.TouchesBorder[run.Component] ? OutsideRegion : regions.RegionOfGap[run.Component];
    if (region == NoRegion)
      continue;
    for (std::int64_t v = run.First; v <= run.Last;)
    {
      const std::int32_t owner = voxelOwner[v];
      std::int64_t end = v + 1;
      while (end <= run.Last && voxelOwner[end] == owner)
        ++end;
      if (owner >= 0)
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
  return regionOfTet;
}
} // namespace cbc3d
