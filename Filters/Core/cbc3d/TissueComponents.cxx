#include "cbc3d/TissueComponents.h"

namespace cbc3d
{
namespace
{
// Labels the 6-connected components of the voxels for which `inRegion` holds, linking
// face-neighbours for which `same` holds (a breadth-first flood fill). Calls `found(size,
// touchesBorder)` once per component, in the order of their first voxel.
template <typename InRegion, typename Same, typename Found>
std::vector<std::int32_t> FloodComponents(const LabelImage& image, InRegion inRegion, Same same, Found found)
{
  std::vector<std::int32_t> componentOfVoxel(image.Labels.size(), -1);
  const auto& d = image.Dimensions;
  const std::int64_t strides[3] = { 1, d[0], std::int64_t(d[0]) * d[1] };
  std::vector<std::int64_t> queue;
  std::int32_t count = 0;
  for (std::int64_t seed = 0; seed < std::int64_t(image.Labels.size()); ++seed)
  {
    if (componentOfVoxel[seed] >= 0 || !inRegion(seed))
    {
      continue;
    }
    componentOfVoxel[seed] = count;
    queue.assign(1, seed);
    bool border = false;
    for (std::size_t next = 0; next < queue.size(); ++next)
    {
      const std::int64_t voxel = queue[next];
      const std::int64_t ijk[3] = { voxel % d[0], (voxel / d[0]) % d[1], voxel / strides[2] };
      for (int axis = 0; axis < 3; ++axis)
      {
        for (const int step : { -1, 1 })
        {
          const std::int64_t moved = ijk[axis] + step;
          if (moved < 0 || moved >= d[axis])
          {
            border = true;
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
    found(seed, static_cast<std::int64_t>(queue.size()), border);
    ++count;
  }
  return componentOfVoxel;
}
} // namespace

TissueComponents FindTissueComponents(const LabelImage& image)
{
  TissueComponents result;
  result.ComponentOfVoxel = FloodComponents(
    image, [&](std::int64_t v) { return image.IsTissue(image.Labels[v]); },
    [&](std::int64_t a, std::int64_t b) { return image.Labels[a] == image.Labels[b]; },
    [&](std::int64_t seed, std::int64_t size, bool) {
      result.Label.push_back(image.Labels[seed]);
      result.Size.push_back(size);
    });
  return result;
}

BackgroundComponents FindBackgroundComponents(const LabelImage& image)
{
  BackgroundComponents result;
  result.ComponentOfVoxel = FloodComponents(
    image, [&](std::int64_t v) { return image.IsBackground(image.Labels[v]); },
    [](std::int64_t, std::int64_t) { return true; },
    [&](std::int64_t, std::int64_t size, bool border) {
      result.Size.push_back(size);
      result.TouchesBorder.push_back(border ? 1 : 0);
    });
  return result;
}
} // namespace cbc3d
