#include "cbc3d/sampling/TetVoxelSampler.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace cbc3d
{
void LabelCounts::Add(std::int32_t label, std::int64_t weight)
{
  for (auto& entry : this->Counts)
  {
    if (entry.first == label)
    {
      entry.second += weight;
      return;
    }
  }
  this->Counts.emplace_back(label, weight);
}

std::int64_t LabelCounts::Of(std::int32_t label) const
{
  for (const auto& entry : this->Counts)
  {
    if (entry.first == label)
    {
      return entry.second;
    }
  }
  return 0;
}

bool LabelCounts::Majority(const LabelImage& image, std::int32_t& label) const
{
  std::int64_t best = 0;
  for (const auto& entry : this->Counts)
  {
    const bool betterTie = best > 0 && entry.second == best &&
      (image.IsTissue(entry.first) != image.IsTissue(label) ? image.IsTissue(entry.first)
                                                            : entry.first < label);
    if (entry.second > best || betterTie)
    {
      best = entry.second;
      label = entry.first;
    }
  }
  return best > 0;
}

std::int64_t LabelCounts::Total() const
{
  std::int64_t total = 0;
  for (const auto& entry : this->Counts)
  {
    total += entry.second;
  }
  return total;
}

std::int64_t LabelCounts::TissueTotal(const LabelImage& image) const
{
  std::int64_t total = 0;
  for (const auto& entry : this->Counts)
  {
    total += image.IsTissue(entry.first) ? entry.second : 0;
  }
  return total;
}

bool LabelCounts::MajorityTissue(const LabelImage& image, std::int32_t& label) const
{
  std::int64_t best = 0;
  for (const auto& entry : this->Counts)
  {
    if (image.IsTissue(entry.first) &&
      (entry.second > best || (entry.second == best && entry.first < label)))
    {
      best = entry.second;
      label = entry.first;
    }
  }
  return best > 0;
}

namespace
{
// A direction in index space that no lattice face plane contains: a point on a face belongs
// to the tet this direction points into.
const Eigen::Vector3d TieBreak(1.0, 0.31830988618379067, 0.10132118364233778);

// Barycentric test in index space with the tie-break above for points on faces.
struct IndexSpaceTet
{
  Eigen::Vector3d Base;
  Eigen::Matrix3d ToBarycentric;
  Eigen::Vector3d Growth; // how the barycentric coordinates change along TieBreak
  Eigen::Vector3d Lower, Upper;

  explicit IndexSpaceTet(const std::array<Eigen::Vector3d, 4>& index)
  {
    this->Base = index[0];
    Eigen::Matrix3d edges;
    edges << index[1] - index[0], index[2] - index[0], index[3] - index[0];
    this->ToBarycentric = edges.inverse();
    this->Growth = this->ToBarycentric * TieBreak;
    this->Lower = this->Upper = index[0];
    for (int v = 1; v < 4; ++v)
    {
      this->Lower = this->Lower.cwiseMin(index[v]);
      this->Upper = this->Upper.cwiseMax(index[v]);
    }
  }

  Eigen::Vector3d Barycentric(const Eigen::Vector3d& point) const
  {
    return this->ToBarycentric * (point - this->Base);
  }

  /// Whether the point with barycentric coordinates b (of corners 1-3) is inside.
  bool Contains(const Eigen::Vector3d& b) const
  {
    constexpr double tolerance = 1e-9;
    const double b0 = 1.0 - b.sum();
    if (b.minCoeff() < -tolerance || b0 < -tolerance)
    {
      return false;
    }
    // On a face (a coordinate near zero): inside only if moving along TieBreak enters the tet,
    // that is, if that coordinate grows along it.
    for (int i = 0; i < 3; ++i)
    {
      if (b[i] <= tolerance && this->Growth[i] <= 0.0)
      {
        return false;
      }
    }
    return !(b0 <= tolerance && -this->Growth.sum() <= 0.0);
  }
};

// The inside samples of one row of the sampling grid: i from First to Last (inclusive; empty
// when First > Last). Along a row each barycentric condition of IndexSpaceTet::Contains holds on
// a half-line, so the inside samples are one run: its ends are estimated from the four linear
// coordinates, then settled by the exact test on the few samples around each end.
struct RowRun
{
  std::int64_t First = 0, Last = -1;
};

RowRun InsideRun(const IndexSpaceTet& tet, const Eigen::Vector3d& rowStart, const Eigen::Vector3d& rowStep,
  std::int64_t first, std::int64_t last)
{
  const Eigen::Vector4d value(1.0 - rowStart.sum(), rowStart[0], rowStart[1], rowStart[2]);
  const Eigen::Vector4d slope(-rowStep.sum(), rowStep[0], rowStep[1], rowStep[2]);
  // A looser bound than Contains's tolerance, so the estimate never cuts an inside sample.
  constexpr double loose = 1e-6;
  double lower = 0.0, upper = double(last - first);
  for (int c = 0; c < 4; ++c)
  {
    if (slope[c] > 0.0)
      lower = std::max(lower, (-loose - value[c]) / slope[c]);
    else if (slope[c] < 0.0)
      upper = std::min(upper, (-loose - value[c]) / slope[c]);
    else if (value[c] < -loose)
      return {};
  }
  if (!(lower <= upper + 2.0))
  {
    return {};
  }
  auto inside = [&](std::int64_t i) { return tet.Contains(rowStart + double(i - first) * rowStep); };
  // A sample before floor(lower) or after ceil(upper) has a coordinate below -loose, far below
  // Contains's -1e-9 (a rounding error is some 1e-12 here): the exact tests start there.
  RowRun run;
  run.First = std::max(first, first + static_cast<std::int64_t>(std::floor(lower)));
  run.Last = std::min(last, first + static_cast<std::int64_t>(std::ceil(upper)));
  while (run.First <= run.Last && !inside(run.First))
    ++run.First;
  while (run.Last >= run.First && !inside(run.Last))
    --run.Last;
  return run;
}

// The voxels first..last of stored row (j, k), whole (their centres are the samples): each run
// of one label is added at once, which leaves the counts as adding them one by one would (the
// same labels in the same order, the same whole sums). Returns the voxels.
std::int64_t AddVoxelRun(const LabelImage& image, int j, int k, int first, int last,
  LabelCounts& counts, std::int32_t owner, std::int32_t* voxelOwner)
{
  image.ForEachRun(j, k, first, last,
    [&](std::int32_t label, int voxels, int) { counts.Add(label, VoxelWeight * voxels); });
  if (voxelOwner)
  {
    const std::int64_t start = image.VoxelIndex(first, j, k);
    std::fill(voxelOwner + start, voxelOwner + start + (last - first) + 1, owner);
  }
  return last - first + 1;
}

// Samples each voxel at the centres of a subdivision^3 sub-grid; returns the samples taken.
std::int64_t SampleGrid(const LabelImage& image, const IndexSpaceTet& tet, int subdivision,
  LabelCounts& counts, std::int32_t owner, std::int32_t* voxelOwner)
{
  const std::int64_t weight = VoxelWeight / (std::int64_t(subdivision) * subdivision * subdivision);
  const double step = 1.0 / subdivision;
  const double offset = 0.5 * step - 0.5; // 0 at subdivision 1: the voxel centres
  std::array<std::int64_t, 3> first, last, inImageFirst, inImageLast;
  const std::array<int, 3> storedFirst = image.StoredLower, storedLast = image.StoredUpper();
  for (int a = 0; a < 3; ++a)
  {
    first[a] = static_cast<std::int64_t>(std::ceil((tet.Lower[a] - offset) / step - 1e-9));
    last[a] = static_cast<std::int64_t>(std::floor((tet.Upper[a] - offset) / step + 1e-9));
    // The samples inside the stored box along this axis: centres from its first voxel - 0.5 to
    // its last + 0.5 (exact: the step is a power of two).
    inImageFirst[a] = static_cast<std::int64_t>(std::ceil((storedFirst[a] - 0.5 - offset) / step));
    inImageLast[a] = static_cast<std::int64_t>(std::ceil((storedLast[a] + 0.5 - offset) / step)) - 1;
  }
  // Beyond the image is background, as the image border is for boundary voxels: a tet that
  // reaches out of a field of view that cuts the tissue counts what lies outside. Beyond the
  // stored box the image holds that same background, so it counts the same way.
  const bool outsideCounts = !image.BackgroundLabels.empty();
  const std::int32_t outside = outsideCounts ? image.BackgroundLabels.front() : 0;
  auto addOutside = [&](std::int64_t n) -> std::int64_t {
    if (!outsideCounts || n <= 0)
    {
      return 0;
    }
    counts.Add(outside, weight * n);
    return n;
  };
  const Eigen::Vector3d rowStep = tet.ToBarycentric.col(0) * step;
  std::int64_t samples = 0;
  for (std::int64_t k = first[2]; k <= last[2]; ++k)
  {
    for (std::int64_t j = first[1]; j <= last[1]; ++j)
    {
      const Eigen::Vector3d rowStart = tet.Barycentric(Eigen::Vector3d(offset + first[0] * step, offset + j * step, offset + k * step));
      const RowRun run = InsideRun(tet, rowStart, rowStep, first[0], last[0]);
      if (run.First > run.Last)
      {
        continue;
      }
      const bool rowInImage = j >= inImageFirst[1] && j <= inImageLast[1] && k >= inImageFirst[2] && k <= inImageLast[2];
      const std::int64_t from = rowInImage ? std::max(run.First, inImageFirst[0]) : run.Last + 1;
      const std::int64_t to = rowInImage ? std::min(run.Last, inImageLast[0]) : run.Last;
      // In sample order: those before the image, those in it, those after.
      samples += addOutside(std::min(from, run.Last + 1) - run.First);
      const int vj = std::clamp(static_cast<int>(std::lround(offset + j * step)), storedFirst[1], storedLast[1]);
      const int vk = std::clamp(static_cast<int>(std::lround(offset + k * step)), storedFirst[2], storedLast[2]);
      const std::int64_t rowVoxels = image.VoxelIndex(storedFirst[0], vj, vk) - storedFirst[0];
      if (subdivision == 1 && from <= to)
      {
        samples += AddVoxelRun(image, vj, vk, int(from), int(to), counts, owner, voxelOwner);
        samples += addOutside(run.Last - to);
        continue;
      }
      for (std::int64_t i = from; i <= to; ++i)
      {
        const int vi = std::clamp(static_cast<int>(std::lround(offset + i * step)), storedFirst[0], storedLast[0]);
        const std::int64_t voxel = rowVoxels + vi;
        counts.Add(image.Labels[voxel], weight);
        if (voxelOwner && subdivision == 1)
        {
          voxelOwner[voxel] = owner;
        }
        ++samples;
      }
      samples += addOutside(run.Last - std::max(to, from - 1));
    }
  }
  return samples;
}
} // namespace

int SampleTetLabels(const LabelImage& image, const std::array<Eigen::Vector3d, 4>& corners,
  LabelCounts& counts, std::int32_t owner, std::int32_t* voxelOwner)
{
  counts.Clear();
  std::array<Eigen::Vector3d, 4> index;
  for (int v = 0; v < 4; ++v)
  {
    index[v] = image.WorldToIndex(corners[v]);
  }
  const IndexSpaceTet tet(index);
  for (int subdivision = 1; subdivision <= 16; subdivision *= 2)
  {
    if (SampleGrid(image, tet, subdivision, counts, owner, voxelOwner) > 0)
    {
      return subdivision;
    }
  }
  return 0;
}
} // namespace cbc3d
