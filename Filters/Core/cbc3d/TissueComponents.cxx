#include "cbc3d/TissueComponents.h"

namespace cbc3d
{
TissueComponents FindTissueComponents(const LabelImage& image)
{
  TissueComponents result;
  result.ComponentOfVoxel.assign(image.Labels.size(), -1);
  const auto& d = image.Dimensions;
  const std::int64_t strides[3] = { 1, d[0], std::int64_t(d[0]) * d[1] };
  std::vector<std::int64_t> queue;
  for (std::int64_t seed = 0; seed < std::int64_t(image.Labels.size()); ++seed)
  {
    const std::int32_t label = image.Labels[seed];
    if (result.ComponentOfVoxel[seed] >= 0 || !image.IsTissue(label))
    {
      continue;
    }
    const std::int32_t component = static_cast<std::int32_t>(result.Label.size());
    result.ComponentOfVoxel[seed] = component;
    queue.assign(1, seed);
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
            continue;
          }
          const std::int64_t neighbour = voxel + step * strides[axis];
          if (result.ComponentOfVoxel[neighbour] < 0 && image.Labels[neighbour] == label)
          {
            result.ComponentOfVoxel[neighbour] = component;
            queue.push_back(neighbour);
          }
        }
      }
    }
    result.Label.push_back(label);
    result.Size.push_back(static_cast<std::int64_t>(queue.size()));
  }
  return result;
}
} // namespace cbc3d
