#include "cbc3d/TissueComponents.h"

#include "cbc3d/DisjointSets.h"

#include <algorithm>
#include <array>

namespace cbc3d
{
namespace
{
// Labels the 6-connected components of the voxels of the box [lower, upper] (inclusive) for
// which `inRegion` holds, linking face-neighbours for which `same` holds. Calls
// `found(seed, size, touchesBoxFace)` once per component, in the order of their first voxel;
// voxels outside the box stay -1. The flood moves by runs along x, so it costs a division per
// run, not three per voxel.
template <typename InRegion, typename Same, typename Found>
std::vector<std::int32_t> FloodComponents(const LabelImage& image, const std::array<int, 3>& lower,
  const std::array<int, 3>& upper, InRegion inRegion, Same same, Found found)
{
  // Indexed like the stored labels: row and slice are the stored box's strides.
  std::vector<std::int32_t> componentOfVoxel(image.Labels.size(), -1);
  const std::array<std::int64_t, 3> strides = image.VoxelStrides();
  const std::int64_t row = strides[1], slice = strides[2];
  struct Run
  {
    std::int64_t J, K;
    std::int64_t First, Last; // voxel indices of the run's ends, inclusive
  };
  std::vector<Run> queue;
  std::int32_t count = 0;
  std::int64_t size = 0;
  bool boxFace = false;
  // Claims the unclaimed run through `voxel` (in row j, k) and queues it.
  auto claimRun = [&](std::int64_t voxel, std::int64_t j, std::int64_t k) {
    const std::int64_t rowStart = image.VoxelIndex(0, int(j), int(k)); // may lie before the box
    std::int64_t first = voxel, last = voxel;
    componentOfVoxel[voxel] = count;
    while (first - rowStart > lower[0] && componentOfVoxel[first - 1] < 0 && inRegion(first - 1) &&
      same(first, first - 1))
      componentOfVoxel[--first] = count;
    while (last - rowStart < upper[0] && componentOfVoxel[last + 1] < 0 && inRegion(last + 1) &&
      same(last, last + 1))
      componentOfVoxel[++last] = count;
    boxFace = boxFace || first - rowStart == lower[0] || last - rowStart == upper[0];
    size += last - first + 1;
    queue.push_back({ j, k, first, last });
  };
  for (std::int64_t k = lower[2]; k <= upper[2]; ++k)
    for (std::int64_t j = lower[1]; j <= upper[1]; ++j)
      for (std::int64_t i = lower[0]; i <= upper[0]; ++i)
      {
        const std::int64_t seed = image.VoxelIndex(int(i), int(j), int(k));
        if (componentOfVoxel[seed] >= 0 || !inRegion(seed))
        {
          continue;
        }
        queue.clear();
        size = 0;
        boxFace = false;
        claimRun(seed, j, k);
        for (std::size_t next = 0; next < queue.size(); ++next)
        {
          const Run run = queue[next];
          const std::int64_t neighbours[4][2] = { { run.J - 1, run.K }, { run.J + 1, run.K },
            { run.J, run.K - 1 }, { run.J, run.K + 1 } };
          for (const auto& [nj, nk] : neighbours)
          {
            if (nj < lower[1] || nj > upper[1] || nk < lower[2] || nk > upper[2])
            {
              boxFace = true;
              continue;
            }
            const std::int64_t offset = (nj - run.J) * row + (nk - run.K) * slice;
            for (std::int64_t voxel = run.First; voxel <= run.Last; ++voxel)
            {
              const std::int64_t neighbour = voxel + offset;
              if (componentOfVoxel[neighbour] < 0 && inRegion(neighbour) && same(voxel, neighbour))
              {
                claimRun(neighbour, nj, nk);
              }
            }
          }
        }
        found(seed, size, boxFace);
        ++count;
      }
  return componentOfVoxel;
}

// The tissue runs of the box [lower, upper], row by row (x fastest rows, in raster order), with
// each row's first run: row r of the box holds runs RowFirst[r] .. RowFirst[r + 1] - 1.
struct BoxRuns
{
  struct Run
  {
    int Start, End; // x, inclusive
    std::int32_t Label;
  };
  std::vector<Run> Runs;
  std::vector<std::int64_t> RowFirst;
};

BoxRuns CollectTissueRuns(const LabelImage& image, const std::array<int, 3>& lower,
  const std::array<int, 3>& upper)
{
  BoxRuns box;
  box.RowFirst.push_back(0);
  for (int k = lower[2]; k <= upper[2]; ++k)
    for (int j = lower[1]; j <= upper[1]; ++j)
    {
      image.ForEachRun(j, k, lower[0], upper[0], [&](std::int32_t label, int voxels, int x) {
        if (image.IsTissue(label))
          box.Runs.push_back({ x, x + voxels - 1, label });
      });
      box.RowFirst.push_back(static_cast<std::int64_t>(box.Runs.size()));
    }
  return box;
}

// Joins the overlapping runs of one label of rows a and b (each sorted along x).
void JoinOverlaps(const BoxRuns& box, std::int64_t a, std::int64_t b, DisjointSets& sets)
{
  std::int64_t p = box.RowFirst[a], q = box.RowFirst[b];
  const std::int64_t pEnd = box.RowFirst[a + 1], qEnd = box.RowFirst[b + 1];
  while (p < pEnd && q < qEnd)
  {
    const BoxRuns::Run &u = box.Runs[p], &v = box.Runs[q];
    if (u.Start <= v.End && v.Start <= u.End && u.Label == v.Label)
      sets.Join(p, q);
    // The run that ends first can overlap nothing further along the other row.
    if (u.End < v.End)
      ++p;
    else
      ++q;
  }
}
} // namespace

std::int32_t TissueComponents::ComponentOf(std::int64_t voxel) const
{
  const auto after = std::upper_bound(this->Runs.begin(), this->Runs.end(), voxel,
    [](std::int64_t v, const Run& run) { return v < run.First; });
  return after != this->Runs.begin() && voxel <= std::prev(after)->Last ? std::prev(after)->Component : -1;
}

TissueComponents FindTissueComponents(const LabelImage& image)
{
  TissueComponents result;
  // Only the tissues' box holds tissue.
  std::array<int, 3> lower, upper;
  if (!TissueIndexBounds(image, lower, upper))
  {
    return result;
  }
  const BoxRuns box = CollectTissueRuns(image, lower, upper);
  const std::int64_t rowsPerSlice = upper[1] - lower[1] + 1;
  const std::int64_t rows = static_cast<std::int64_t>(box.RowFirst.size()) - 1;
  DisjointSets sets(box.Runs.size());
  for (std::int64_t r = 0; r < rows; ++r)
  {
    if (r % rowsPerSlice > 0)
      JoinOverlaps(box, r - 1, r, sets);
    if (r >= rowsPerSlice)
      JoinOverlaps(box, r - rowsPerSlice, r, sets);
  }
  // Raster order of the runs is that of their first voxels: a component is numbered when its
  // first run comes, as a flood fill seeded in raster order would number it.
  std::vector<std::int32_t> componentOfRoot(box.Runs.size(), -1);
  result.Runs.reserve(box.Runs.size());
  for (std::int64_t r = 0; r < rows; ++r)
  {
    const int j = lower[1] + int(r % rowsPerSlice), k = lower[2] + int(r / rowsPerSlice);
    const std::int64_t rowStart = image.VoxelIndex(0, j, k); // may lie before the stored box
    for (std::int64_t n = box.RowFirst[r]; n < box.RowFirst[r + 1]; ++n)
    {
      const BoxRuns::Run& run = box.Runs[n];
      std::int32_t& component = componentOfRoot[sets.Find(n)];
      if (component < 0)
      {
        component = static_cast<std::int32_t>(result.Label.size());
        result.Label.push_back(run.Label);
        result.Size.push_back(0);
      }
      result.Size[component] += run.End - run.Start + 1;
      result.Runs.push_back({ rowStart + run.Start, rowStart + run.End, component });
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
    lower = image.StoredLower;
    upper = image.StoredUpper();
  }
  // The layer lies within the stored box: the box holds every voxel but the first background's
  // and one voxel around them, clamped to the image.
  const std::array<int, 3> storedUpper = image.StoredUpper();
  for (int axis = 0; axis < 3; ++axis)
  {
    lower[axis] = std::max(lower[axis] - 1, image.StoredLower[axis]);
    upper[axis] = std::min(upper[axis] + 1, storedUpper[axis]);
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
