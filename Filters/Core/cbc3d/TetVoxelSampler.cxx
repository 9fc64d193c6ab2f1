#include "cbc3d/TetVoxelSampler.h"

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

// Samples each voxel at the centres of a subdivision^3 sub-grid; returns the samples taken.
std::int64_t SampleGrid(const LabelImage& image, const IndexSpaceTet& tet, int subdivision,
  LabelCounts& counts, std::int32_t owner, std::int32_t* voxelOwner)
{
  const std::int64_t weight = VoxelWeight / (std::int64_t(subdivision) * subdivision * subdivision);
  const double step = 1.0 / subdivision;
  const double offset = 0.5 * step - 0.5; // 0 at subdivision 1: the voxel centres
  std::array<std::int64_t, 3> first, last;
  for (int a = 0; a < 3; ++a)
  {
    first[a] = static_cast<std::int64_t>(std::ceil((tet.Lower[a] - offset) / step - 1e-9));
    last[a] = static_cast<std::int64_t>(std::floor((tet.Upper[a] - offset) / step + 1e-9));
  }
  // Beyond the image is background, as the image border is for boundary voxels: a tet that
  // reaches out of a field of view that cuts the tissue counts what lies outside.
  const bool outsideCounts = !image.BackgroundLabels.empty();
  const std::int32_t outside = outsideCounts ? image.BackgroundLabels.front() : 0;
  auto inImage = [&](double x, int a) { return x >= -0.5 && x < image.Dimensions[a] - 0.5; };
  std::int64_t samples = 0;
  Eigen::Vector3d point;
  for (std::int64_t k = first[2]; k <= last[2]; ++k)
  {
    point[2] = offset + k * step;
    for (std::int64_t j = first[1]; j <= last[1]; ++j)
    {
      point[1] = offset + j * step;
      point[0] = offset + first[0] * step;
      // Along a row the barycentric coordinates change by a constant step.
      Eigen::Vector3d b = tet.Barycentric(point);
      const Eigen::Vector3d rowStep = tet.ToBarycentric.col(0) * step;
      for (std::int64_t i = first[0]; i <= last[0]; ++i, b += rowStep)
      {
        point[0] = offset + i * step;
        if (!tet.Contains(b))
        {
          continue;
        }
        if (!(inImage(point[0], 0) && inImage(point[1], 1) && inImage(point[2], 2)))
        {
          if (outsideCounts)
          {
            counts.Add(outside, weight);
            ++samples;
          }
          continue;
        }
        const int vi = std::clamp(static_cast<int>(std::lround(point[0])), 0, image.Dimensions[0] - 1);
        const int vj = std::clamp(static_cast<int>(std::lround(point[1])), 0, image.Dimensions[1] - 1);
        const int vk = std::clamp(static_cast<int>(std::lround(point[2])), 0, image.Dimensions[2] - 1);
        counts.Add(image.LabelAt(vi, vj, vk), weight);
        if (voxelOwner && subdivision == 1)
        {
          voxelOwner[image.VoxelIndex(vi, vj, vk)] = owner;
        }
        ++samples;
      }
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
