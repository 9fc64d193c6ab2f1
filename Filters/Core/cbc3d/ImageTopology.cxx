#include "cbc3d/ImageTopology.h"

#include "cbc3d/Parallel.h"

#include <algorithm>
#include <array>
#include <vector>

namespace cbc3d
{
namespace
{
// The index-space box (inclusive) of one tissue's voxels.
struct LabelBox
{
  std::int32_t Label;
  std::array<int, 3> Lower, Upper;
};

// Every tissue's box in one pass; a label is looked up only where it differs from the last.
std::vector<LabelBox> TissueBoxes(const LabelImage& image)
{
  std::vector<LabelBox> boxes;
  // The stored box holds every tissue voxel, in the image's order.
  const std::array<int, 3> first = image.StoredLower, upper = image.StoredUpper();
  std::size_t last = 0;
  std::int64_t voxel = 0;
  for (int k = first[2]; k <= upper[2]; ++k)
    for (int j = first[1]; j <= upper[1]; ++j)
      for (int i = first[0]; i <= upper[0]; ++i, ++voxel)
      {
        const std::int32_t label = image.Labels[voxel];
        if (last >= boxes.size() || boxes[last].Label != label)
        {
          if (image.IsBackground(label))
          {
            continue;
          }
          last = std::find_if(boxes.begin(), boxes.end(), [label](const LabelBox& b) { return b.Label == label; }) -
            boxes.begin();
          if (last == boxes.size())
          {
            boxes.push_back(LabelBox{ label, { i, j, k }, { i, j, k } });
          }
        }
        LabelBox& box = boxes[last];
        const std::array<int, 3> at = { i, j, k };
        for (int a = 0; a < 3; ++a)
        {
          box.Lower[a] = std::min(box.Lower[a], at[a]);
          box.Upper[a] = std::max(box.Upper[a], at[a]);
        }
      }
  return boxes;
}

// V - E + F of the voxel-face surface of the voxels `inside(voxelIndex)` selects, all of them
// within [lower, upper]. Corners and edges are flagged on the box's corner grid: an edge is
// flagged at its lower corner, one flag array per axis.
template <typename Inside>
std::int64_t VoxelSurfaceEuler(
  const LabelImage& image, const std::array<int, 3>& lower, const std::array<int, 3>& upper, Inside inside)
{
  const auto& d = image.Dimensions;
  const std::array<std::int64_t, 3> n = { upper[0] - lower[0] + 2, upper[1] - lower[1] + 2,
    upper[2] - lower[2] + 2 };
  const std::array<std::int64_t, 3> stride = { 1, n[0], n[0] * n[1] };
  std::vector<unsigned char> corner(n[0] * n[1] * n[2], 0);
  std::array<std::vector<unsigned char>, 3> edge;
  edge.fill(corner);
  const std::array<std::int64_t, 3> voxelStride = image.VoxelStrides(); // one voxel around a tissue is stored
  std::int64_t faces = 0;
  for (int k = lower[2]; k <= upper[2]; ++k)
    for (int j = lower[1]; j <= upper[1]; ++j)
      for (int i = lower[0]; i <= upper[0]; ++i)
      {
        const std::int64_t voxel = image.VoxelIndex(i, j, k);
        if (!inside(voxel))
        {
          continue;
        }
        const std::array<int, 3> at = { i, j, k };
        const std::int64_t base = (i - lower[0]) + n[0] * ((j - lower[1]) + n[1] * (k - lower[2]));
        for (int a = 0; a < 3; ++a)
          for (int side = 0; side < 2; ++side)
          {
            const int neighbour = at[a] + (side ? 1 : -1);
            if (neighbour >= 0 && neighbour < d[a] && inside(voxel + (side ? 1 : -1) * voxelStride[a]))
            {
              continue;
            }
            // The face across axis a spans the two other axes b and c.
            ++faces;
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            const std::int64_t origin = base + side * stride[a];
            corner[origin] = corner[origin + stride[b]] = corner[origin + stride[c]] =
              corner[origin + stride[b] + stride[c]] = 1;
            edge[b][origin] = edge[b][origin + stride[c]] = 1;
            edge[c][origin] = edge[c][origin + stride[b]] = 1;
          }
      }
  auto flagged = [](const std::vector<unsigned char>& flags) {
    return static_cast<std::int64_t>(std::count(flags.begin(), flags.end(), 1));
  };
  return flagged(corner) - flagged(edge[0]) - flagged(edge[1]) - flagged(edge[2]) + faces;
}

ImageTopology Measure(const LabelImage& image, bool withWhole, int numberOfThreads)
{
  ImageTopology topology;
  const std::vector<LabelBox> boxes = TissueBoxes(image);
  if (boxes.empty())
  {
    return topology;
  }
  LabelBox whole = boxes[0];
  for (const LabelBox& box : boxes)
  {
    for (int a = 0; a < 3; ++a)
    {
      whole.Lower[a] = std::min(whole.Lower[a], box.Lower[a]);
      whole.Upper[a] = std::max(whole.Upper[a], box.Upper[a]);
    }
  }
  // One job per tissue, and the whole body last; the jobs share nothing but the image.
  const std::vector<std::int32_t>& labels = image.Labels;
  const int jobs = static_cast<int>(boxes.size()) + (withWhole ? 1 : 0);
  std::vector<std::int64_t> euler(jobs, 0);
#pragma omp parallel for schedule(dynamic, 1) num_threads(ThreadCount(numberOfThreads))
  for (int job = 0; job < jobs; ++job)
  {
    if (job == static_cast<int>(boxes.size()))
    {
      euler[job] = VoxelSurfaceEuler(
        image, whole.Lower, whole.Upper, [&image](std::int64_t v) { return image.IsTissue(image.Labels[v]); });
      continue;
    }
    const LabelBox& box = boxes[job];
    euler[job] = VoxelSurfaceEuler(
      image, box.Lower, box.Upper, [&labels, &box](std::int64_t v) { return labels[v] == box.Label; });
  }
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    topology.TissueSurfaceEuler[boxes[i].Label] = euler[i];
  }
  topology.WholeSurfaceEuler = withWhole ? euler.back() : 0;
  return topology;
}
} // namespace

ImageTopology MeasureImageTopology(const LabelImage& image, int numberOfThreads)
{
  return Measure(image, true, numberOfThreads);
}

std::map<std::int32_t, std::int64_t> ImageSurfaceEuler(const LabelImage& image, int numberOfThreads)
{
  return Measure(image, false, numberOfThreads).TissueSurfaceEuler;
}
} // namespace cbc3d
