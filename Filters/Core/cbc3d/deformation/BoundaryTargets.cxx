#include "cbc3d/deformation/BoundaryTargets.h"

#include <algorithm>
#include <map>
#include <set>

namespace cbc3d
{
namespace
{
// Neighbour offsets that a pattern blocks once a voxel is taken.
std::vector<std::array<int, 3>> BlockedOffsets(TargetPattern pattern)
{
  std::vector<std::array<int, 3>> offsets;
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di)
      {
        const int order = std::abs(di) + std::abs(dj) + std::abs(dk); // 1 face, 2 edge, 3 vertex
        const bool blocked = order > 0 &&
          ((pattern == TargetPattern::Face && order == 1) || (pattern == TargetPattern::Edge && order <= 2) ||
            pattern == TargetPattern::Vertex);
        if (blocked)
        {
          offsets.push_back({ di, dj, dk });
        }
      }
  return offsets;
}
} // namespace

Eigen::Vector3d TargetPosition(const LabelImage& image, std::int64_t voxel, TargetPlacement placement)
{
  const auto& d = image.Dimensions;
  const auto [i, j, k] = image.VoxelCoordinates(voxel);
  Eigen::Vector3d index(i, j, k);
  if (placement == TargetPlacement::VoxelFace)
  {
    const std::int32_t label = image.Labels[voxel];
    Eigen::Vector3d toward = Eigen::Vector3d::Zero(); // the sum of steps to other labels
    int others = 0;
    const int faces[6][3] = { { -1, 0, 0 }, { 1, 0, 0 }, { 0, -1, 0 }, { 0, 1, 0 }, { 0, 0, -1 }, { 0, 0, 1 } };
    for (const auto& f : faces)
    {
      const int a = i + f[0], b = j + f[1], c = k + f[2];
      if (a < 0 || b < 0 || c < 0 || a >= d[0] || b >= d[1] || c >= d[2] || image.LabelOf(a, b, c) != label)
      {
        toward += Eigen::Vector3d(f[0], f[1], f[2]);
        ++others;
      }
    }
    if (others > 0)
    {
      index += 0.5 * toward / double(others);
    }
  }
  return image.IndexToWorld(index);
}

std::vector<BoundaryTarget> FindBoundaryTargets(const LabelImage& image, TargetPattern pattern,
  TargetPlacement placement)
{
  return FindBoundaryTargets(image, TissueBoundaryVoxels(image), pattern, placement);
}

std::vector<BoundaryTarget> FindBoundaryTargets(const LabelImage& image, const TissueVoxels& boundary,
  TargetPattern pattern, TargetPlacement placement)
{
  const auto& d = image.Dimensions;
  const auto blocked = BlockedOffsets(pattern);
  // Whether each boundary voxel may still be taken, per tissue in its list's order: only
  // boundary voxels are ever looked at, so no flag per voxel of the image (107 MB on the brain
  // upsampled 4x per axis).
  std::map<std::int32_t, std::vector<char>> allowed;
  for (const auto& [tissue, voxels] : boundary)
  {
    allowed[tissue].assign(voxels.size(), 1);
  }
  auto block = [&](std::int64_t voxel) {
    const auto list = boundary.find(image.Labels[voxel]);
    if (list == boundary.end())
    {
      return; // not a tissue voxel
    }
    const auto at = std::lower_bound(list->second.begin(), list->second.end(), voxel);
    if (at != list->second.end() && *at == voxel)
    {
      allowed[list->first][at - list->second.begin()] = 0;
    }
  };
  std::set<LabelSet> earlierTissues;
  std::vector<BoundaryTarget> targets;
  auto labelOf = [&](int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= d[0] || j >= d[1] || k >= d[2])
    {
      return OutsideLabel;
    }
    const std::int32_t label = image.LabelOf(i, j, k);
    return image.IsTissue(label) ? label : OutsideLabel;
  };
  // Ascending labels, each tissue's boundary voxels in x-fastest order: the order of a scan of
  // the whole image, which the blocking depends on.
  for (const auto& [tissue, voxels] : boundary)
  {
    std::set<LabelSet> thisTissue;
    const std::vector<char>& open = allowed[tissue];
    for (std::size_t v = 0; v < voxels.size(); ++v)
    {
      const std::int64_t voxel = voxels[v];
      if (!open[v])
      {
        continue;
      }
      const auto [i, j, k] = image.VoxelCoordinates(voxel);
      LabelSet labels = { tissue };
      const int faces[6][3] = { { -1, 0, 0 }, { 1, 0, 0 }, { 0, -1, 0 }, { 0, 1, 0 }, { 0, 0, -1 }, { 0, 0, 1 } };
      for (const auto& f : faces)
      {
        const std::int32_t other = labelOf(i + f[0], j + f[1], k + f[2]);
        if (std::find(labels.begin(), labels.end(), other) == labels.end())
        {
          labels.push_back(other);
        }
      }
      std::sort(labels.begin(), labels.end());
      if (earlierTissues.count(labels))
      {
        continue; // this interface was sampled from an earlier tissue's side
      }
      thisTissue.insert(labels);
      targets.push_back({ TargetPosition(image, voxel, placement), labels });
      for (const auto& o : blocked)
      {
        const int ni = i + o[0], nj = j + o[1], nk = k + o[2];
        if (image.IsStored(ni, nj, nk))
        {
          block(image.VoxelIndex(ni, nj, nk));
        }
      }
    }
    earlierTissues.insert(thisTissue.begin(), thisTissue.end());
  }
  return targets;
}

TissueVoxels WithinWindow(const LabelImage& image, TissueVoxels boundary, const BoundaryWindow& window)
{
  if (!window.Set)
  {
    return boundary;
  }
  TissueVoxels inside;
  for (const auto& [tissue, voxels] : boundary)
  {
    for (const std::int64_t voxel : voxels)
    {
      const double along = window.Normal.dot(image.VoxelCentre(voxel));
      if (along >= window.Lower && along <= window.Upper)
      {
        inside[tissue].push_back(voxel);
      }
    }
  }
  return inside;
}
} // namespace cbc3d
