#include "cbc3d/soundlabels/SoundLabels.h"

#include "cbc3d/soundlabels/ManifoldRepair.h"
#include "cbc3d/soundlabels/StrayComponents.h"

#include <algorithm>

namespace cbc3d
{
namespace
{
// Rounds of stray removal, each followed by repairs around what it changed.
constexpr int CleanupRounds = 4;

std::vector<PointId> VerticesOf(const std::vector<Tet>& tets, const std::vector<std::int64_t>& changed)
{
  std::vector<PointId> vertices;
  for (const std::int64_t t : changed)
    vertices.insert(vertices.end(), tets[t].begin(), tets[t].end());
  return vertices;
}
} // namespace

SoundLabelsResult MakeLabelsSound(const LabelImage& image, const ImageRegions& regions,
  const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets,
  const std::vector<TetNeighbours>& across,
  const std::vector<LabelCounts>& counts, const VoxelOwners& voxelOwner,
  const std::map<std::int64_t, std::int32_t>& pinned, std::int32_t background,
  std::vector<std::int32_t>& labels, int numberOfThreads)
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
  // The repair must not open a cavity of the image: it reads which cavity each tet stands for.
  const std::vector<std::int32_t> regionOfTet = BackgroundRegionOfTets(image, regions, voxelOwner, points, tets, numberOfThreads);
  SoundLabelsResult result;
  ManifoldRepairResult repair = RepairManifoldLabels(
    points, tets, across, background, votes, classes, {}, numberOfThreads, regionOfTet);
  result.Repairs += repair.Repairs;
  bool unfinished = repair.Unrepaired > 0; // some repair stopped at its work bound
  for (int round = 0; round < CleanupRounds; ++round)
  {
    std::vector<std::int64_t> changed;
    result.StrayPieces +=
      RemoveStrayComponents(tets, across, background, votes, voxelOwner, regions, classes, changed);
    if (changed.empty())
    {
      break;
    }
    repair = RepairManifoldLabels(
      points, tets, across, background, votes, classes, VerticesOf(tets, changed), 1, regionOfTet);
    result.Repairs += repair.Repairs;
    unfinished = unfinished || repair.Unrepaired > 0;
  }
  // A later repair looks only around later changes: count what an unfinished one left anywhere.
  result.Unrepaired = unfinished ? CountNonManifoldVertices(points, tets, across, background, classes) : 0;
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
