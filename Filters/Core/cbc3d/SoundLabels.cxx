#include "cbc3d/SoundLabels.h"

#include "cbc3d/ManifoldRepair.h"
#include "cbc3d/StrayComponents.h"

#include <algorithm>

namespace cbc3d
{
namespace
{
// Rounds of stray removal, each followed by repairs around what it changed.
constexpr int CleanupRounds = 4;

// The image components the mesh should keep; the background's cavities only when asked (their
// flood fill is the costly part, and most meshes have no cavity to check).
ImageRegions KeptRegions(const LabelImage& image, const TissueComponents& tissues, int minimumVoxels,
  std::int32_t background, bool withCavities)
{
  const BackgroundComponents gaps = withCavities ? FindBackgroundComponents(image) : BackgroundComponents();
  ImageRegions regions;
  const std::int32_t tissueCount = static_cast<std::int32_t>(tissues.Label.size());
  for (std::int32_t c = 0; c < tissueCount; ++c)
  {
    regions.ClassOfRegion.push_back(tissues.Label[c]);
    regions.Speck.push_back(tissues.Size[c] < minimumVoxels);
  }
  for (std::size_t c = 0; c < gaps.Size.size(); ++c)
  {
    regions.ClassOfRegion.push_back(background);
    regions.Speck.push_back(0);
  }
  regions.RegionOfVoxel.assign(image.Labels.size(), -1);
  for (std::size_t v = 0; v < image.Labels.size(); ++v)
  {
    const std::int32_t tissue = tissues.ComponentOfVoxel[v];
    const std::int32_t gap = withCavities ? gaps.ComponentOfVoxel[v] : -1;
    if (tissue >= 0)
      regions.RegionOfVoxel[v] = tissue;
    else if (gap >= 0 && !gaps.TouchesBorder[gap] && gaps.Size[gap] >= minimumVoxels)
      regions.RegionOfVoxel[v] = tissueCount + gap;
  }
  return regions;
}

std::vector<PointId> VerticesOf(const std::vector<Tet>& tets, const std::vector<std::int64_t>& changed)
{
  std::vector<PointId> vertices;
  for (const std::int64_t t : changed)
    vertices.insert(vertices.end(), tets[t].begin(), tets[t].end());
  return vertices;
}
} // namespace

SoundLabelsResult MakeLabelsSound(const LabelImage& image, const TissueComponents& components,
  int minimumVoxels, const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets,
  const std::vector<std::array<std::int64_t, 4>>& across,
  const std::vector<LabelCounts>& counts, const std::vector<std::int32_t>& voxelOwner,
  const std::map<std::int64_t, std::int32_t>& pinned, std::int32_t background,
  std::vector<std::int32_t>& labels)
{
  std::vector<std::int32_t> classes(labels.size());
  for (std::size_t t = 0; t < labels.size(); ++t)
    classes[t] = labels[t] != background && image.IsTissue(labels[t]) ? labels[t] : background;
  const std::vector<std::int32_t> original(classes);
  const ClassVotes votes = [&](std::int64_t t, std::int32_t cls) {
    const auto pin = pinned.find(t);
    const std::int64_t bonus = pin != pinned.end() && pin->second == cls ? PinnedVotes : 0;
    return bonus + (cls == background ? counts[t].Total() - counts[t].TissueTotal(image) : counts[t].Of(cls));
  };
  SoundLabelsResult result;
  ManifoldRepairResult repair = RepairManifoldLabels(points, tets, across, background, votes, classes);
  result.Repairs += repair.Repairs;
  const ImageRegions regions = KeptRegions(image, components, minimumVoxels, background,
    HasEnclosedBackground(tets, across, background, classes));
  for (int round = 0; round < CleanupRounds; ++round)
  {
    std::vector<std::int64_t> changed;
    result.StrayPieces +=
      RemoveStrayComponents(tets, across, background, votes, voxelOwner, regions, classes, changed);
    if (changed.empty())
    {
      break;
    }
    repair = RepairManifoldLabels(points, tets, across, background, votes, classes, VerticesOf(tets, changed));
    result.Repairs += repair.Repairs;
    }
  result.Unrepaired = repair.Unrepaired;
  for (std::size_t t = 0; t < labels.size(); ++t)
  {
    if (classes[t] != original[t])
    {
      labels[t] = classes[t];
      ++result.Relabelled;
    }
  }
  return result;
}
} // namespace cbc3d
