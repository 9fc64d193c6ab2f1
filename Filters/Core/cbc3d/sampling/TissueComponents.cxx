#include "cbc3d/sampling/TissueComponents.h"

#include "cbc3d/base/DisjointSets.h"

#include <algorithm>
#include <array>
#include <limits>

namespace cbc3d
{
namespace
{
// The runs of the box [lower, upper] whose labels are `member`s, row by row (x fastest rows,
// in raster order), each run of one class (`classOf`; neighbouring runs of one class are one):
// row r of the box holds runs RowFirst[r] .. RowFirst[r + 1] - 1.
struct BoxRuns
{
  struct Run
  {
    int Start, End; // x, inclusive
    std::int32_t Class;
  };
  std::vector<Run> Runs;
  std::vector<std::int64_t> RowFirst;
};

template <typename Member, typename ClassOf>
BoxRuns CollectRuns(const LabelImage& image, const std::array<int, 3>& lower,
  const std::array<int, 3>& upper, Member member, ClassOf classOf)
{
  BoxRuns box;
  box.RowFirst.push_back(0);
  for (int k = lower[2]; k <= upper[2]; ++k)
    for (int j = lower[1]; j <= upper[1]; ++j)
    {
      image.ForEachRun(j, k, lower[0], upper[0], [&](std::int32_t label, int voxels, int x) {
        if (!member(label))
          return;
        const std::int32_t cls = classOf(label);
        if (std::int64_t(box.Runs.size()) > box.RowFirst.back() && box.Runs.back().End == x - 1 &&
          box.Runs.back().Class == cls)
          box.Runs.back().End = x + voxels - 1;
        else
          box.Runs.push_back({ x, x + voxels - 1, cls });
      });
      box.RowFirst.push_back(static_cast<std::int64_t>(box.Runs.size()));
    }
  return box;
}

// Joins the overlapping runs of one class of rows a and b (each sorted along x).
void JoinOverlaps(const BoxRuns& box, std::int64_t a, std::int64_t b, DisjointSets& sets)
{
  std::int64_t p = box.RowFirst[a], q = box.RowFirst[b];
  const std::int64_t pEnd = box.RowFirst[a + 1], qEnd = box.RowFirst[b + 1];
  while (p < pEnd && q < qEnd)
  {
    const BoxRuns::Run &u = box.Runs[p], &v = box.Runs[q];
    if (u.Start <= v.End && v.Start <= u.End && u.Class == v.Class)
      sets.Join(p, q);
    // The run that ends first can overlap nothing further along the other row.
    if (u.End < v.End)
      ++p;
    else
      ++q;
  }
}

// Numbers the components of the box's runs (overlapping runs of one class in neighbouring rows
// join) in raster order of their first runs, as a flood fill seeded in raster order would, and
// lists the runs as voxel indices. Calls `first(component, run, j, k)` at each component's first
// run and `each(component, run, j, k)` at every run.
template <typename First, typename Each>
void NumberComponents(const LabelImage& image, const std::array<int, 3>& lower,
  const std::array<int, 3>& upper, const BoxRuns& box, RunComponents& result, First first, Each each)
{
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
        component = static_cast<std::int32_t>(result.Size.size());
        result.Size.push_back(0);
        first(component, run, j, k);
      }
      result.Size[component] += run.End - run.Start + 1;
      result.Runs.push_back({ rowStart + run.Start, rowStart + run.End, component });
      each(component, run, j, k);
    }
  }
}
} // namespace

std::int32_t RunComponents::ComponentOf(std::int64_t voxel) const
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
  const BoxRuns box = CollectRuns(
    image, lower, upper, [&](std::int32_t label) { return image.IsTissue(label); },
    [](std::int32_t label) { return label; });
  NumberComponents(
    image, lower, upper, box, result,
    [&](std::int32_t, const BoxRuns::Run& run, int, int) { result.Label.push_back(run.Class); },
    [](std::int32_t, const BoxRuns::Run&, int, int) {});
  return result;
}

BackgroundComponents FindBackgroundComponents(const LabelImage& image)
{
  BackgroundComponents result;
  // Every background voxel outside the tissues' box reaches the image border in a straight
  // line, so only the box and one voxel around it need labelling: a component that reaches that
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
  const BoxRuns box = CollectRuns(
    image, lower, upper, [&](std::int32_t label) { return image.IsBackground(label); },
    [](std::int32_t) { return 0; });
  // A side of a piece where the whole image's tissue goes on is no border (see the header).
  std::array<int, 3> borderLower = lower, borderUpper = upper;
  for (int axis = 0; image.HasLatticeBox && axis < 3; ++axis)
  {
    const int last = image.Dimensions[axis] - 1;
    if (lower[axis] == 0 && image.LatticeBoxLower[axis] < 0)
      borderLower[axis] = std::numeric_limits<int>::min();
    if (upper[axis] == last && image.LatticeBoxUpper[axis] > last)
      borderUpper[axis] = std::numeric_limits<int>::max();
  }
  NumberComponents(
    image, lower, upper, box, result,
    [&](std::int32_t, const BoxRuns::Run&, int, int) { result.TouchesBorder.push_back(0); },
    [&](std::int32_t component, const BoxRuns::Run& run, int j, int k) {
      if (run.Start == borderLower[0] || run.End == borderUpper[0] || j == borderLower[1] || j == borderUpper[1] ||
        k == borderLower[2] || k == borderUpper[2])
        result.TouchesBorder[component] = 1;
    });
  return result;
}
} // namespace cbc3d
