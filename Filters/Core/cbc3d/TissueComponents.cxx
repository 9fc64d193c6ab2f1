#include "cbc3d/TissueComponents.h"

#include <algorithm>
#include <array>

namespace cbc3d
{
namespace
{
// Labels the 6-connected components of the voxels of the box [lower, upper] (inclusive) for
// which `inRegion` holds, linking face-neighbours for which `same` holds (a breadth-first flood
// fill). Calls `found(seed, size, touchesBoxFace)` once per component, in the order of their
// first voxel; voxels outside the box stay -1.
template <typename InRegion, typename Same, typename Found>
std::vector<std::int32_t> FloodComponents(const LabelImage& image, const std::array<int, 3>& lower,
  const std::array<int, 3>& upper, InRegion inRegion, Same same, Found found)
{
  std::vector<std::int32_t> componentOfVoxel(image.Labels.size(), -1);
  const auto& d = image.Dimensions;
  const std::int64_t strides[3] = { 1, d[0], std::int64_t(d[0]) * d[1] };
  std::vector<std::int64_t> queue;
  std::int32_t count = 0;
  for (std::int64_t k = lower[2]; k <= upper[2]; ++k)
    for (std::int64_t j = lower[1]; j <= upper[1]; ++j)
      for (std::int64_t i = lower[0]; i <= upper[0]; ++i)
      {
        const std::int64_t seed = i + j * strides[1] + k * strides[2];
        if (componentOfVoxel[seed] >= 0 || !inRegion(seed))
        {
          continue;
        }
        componentOfVoxel[seed] = count;
        queue.assign(1, seed);
        bool boxFace = false;
        for (std::size_t next = 0; next < queue.size(); ++next)
        {
          const std::int64_t voxel = queue[next];
          const std::int64_t ijk[3] = { voxel % d[0], (voxel / d[0]) % d[1], voxel / strides[2] };
          for (int axis = 0; axis < 3; ++axis)
          {
            for (const int step : { -1, 1 })
            {
              const std::int64_t moved = ijk[axis] + step;
              if (moved < lower[axis] || moved > upper[axis])
              {
                boxFace = true;
                continue;
              }
              const std::int64_t neighbour = voxel + step * strides[axis];
              if (componentOfVoxel[neighbour] < 0 && inRegion(neighbour) && same(voxel, neighbour))
              {
                componentOfVoxel[neighbour] = count;
                queue.push_back(neighbour);
              }
            }
          }
        }
        found(seed, static_cast<std::int64_t>(queue.size()), boxFace);
        ++count;
      }
  return componentOfVoxel;
}
} // namespace

TissueComponents FindTissueComponents(const LabelImage& image)
{
  TissueComponents result;
  const std::array<int, 3> lower = { 0, 0, 0 };
  const std::array<int, 3> upper = { image.Dimensions[0] - 1, image.Dimensions[1] - 1, image.Dimensions[2] - 1 };
  result.ComponentOfVoxel = FloodComponents(
    image, lower, upper, [&](std::int64_t v) { return image.IsTissue(image.Labels[v]); },
    [&](std::int64_t a, std::int64_t b) { return image.Labels[a] == image.Labels[b]; },
    [&](std::int64_t seed, std::int64_t size, bool) {
      result.Label.push_back(image.Labels[seed]);
      result.Size.push_back(size);
    });
  for (std::size_t v = 0; v < result.ComponentOfVoxel.size(); ++v)
  {
    if (result.ComponentOfVoxel[v] >= 0)
    {
      result.Voxels.push_back(static_cast<std::int64_t>(v));
    }
  }
  return result;
}

BackgroundComponents FindBackgroundComponents(const LabelImage& image)
{
  BackgroundComponents result;
  // Every background voxel outside the tissues' box reaches the image border in a straight
  // line, so only the box and one voxel around it need the flood: a component that reaches that
  // layer (or the border) is the outside. An image of a small tissue costs what the tissue does.
  std::array<int, 3> lower, upper;
  if (!TissueIndexBounds(image, lower, upper))
  {
    lower = { 0, 0, 0 };
    upper = { image.Dimensions[0] - 1, image.Dimensions[1] - 1, image.Dimensions[2] - 1 };
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    lower[axis] = std::max(lower[axis] - 1, 0);
    upper[axis] = std::min(upper[axis] + 1, image.Dimensions[axis] - 1);
  }
  result.ComponentOfVoxel = FloodComponents(
    image, lower, upper, [&](std::int64_t v) { return image.IsBackground(image.Labels[v]); },
    [](std::int64_t, std::int64_t) { return true; },
    [&](std::int64_t, std::int64_t size, bool border) {
      result.Size.push_back(size);
      result.TouchesBorder.push_back(border ? 1 : 0);
    });
  return result;
}
} // namespace cbc3d
