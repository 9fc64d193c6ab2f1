#include "cbc3d/base/LabelImage.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace cbc3d
{
Eigen::Vector3d LabelImage::IndexToWorld(const Eigen::Vector3d& index) const
{
  return this->Origin + this->Direction * index.cwiseProduct(this->Spacing);
}

Eigen::Vector3d LabelImage::WorldToIndex(const Eigen::Vector3d& world) const
{
  // Direction is orthonormal, so its inverse is its transpose.
  return (this->Direction.transpose() * (world - this->Origin)).cwiseQuotient(this->Spacing);
}

std::vector<std::int32_t> LabelImage::TissueLabels() const
{
  std::set<std::int32_t> seen;
  std::int32_t last = 0;
  bool haveLast = false;
  for (const std::int32_t label : this->Labels)
  {
    // Runs of one label are the common case in label maps; skip the set lookup for them.
    if (haveLast && label == last)
    {
      continue;
    }
    last = label;
    haveLast = true;
    if (this->IsTissue(label))
    {
      seen.insert(label);
    }
  }
  return std::vector<std::int32_t>(seen.begin(), seen.end());
}

Status ValidateLabelImage(const LabelImage& image)
{
  const auto& d = image.Dimensions;
  if (d[0] < 2 || d[1] < 2 || d[2] < 2)
  {
    std::ostringstream msg;
    msg << "the image is " << d[0] << " x " << d[1] << " x " << d[2]
        << " voxels; a 3-D label map with at least 2 voxels along every axis is required";
    return Status::Error(msg.str());
  }
  const auto& n = image.StoredDimensions();
  for (int a = 0; a < 3; ++a)
  {
    if (image.StoredLower[a] < 0 || n[a] < 1 || image.StoredLower[a] + n[a] > d[a])
    {
      return Status::Error("the stored box of labels is not within the image");
    }
  }
  if (image.BackgroundLabels.empty() && std::int64_t(n[0]) * n[1] * n[2] != image.VoxelCount())
  {
    return Status::Error("a stored box of labels needs a background label for the voxels beyond it");
  }
  if (std::int64_t(image.Labels.size()) != std::int64_t(n[0]) * n[1] * n[2])
  {
    return Status::Error("the label array does not have one value per voxel");
  }
  for (int a = 0; a < 3; ++a)
  {
    if (!(image.Spacing[a] > 0.0) || !std::isfinite(image.Spacing[a]))
    {
      return Status::Error("the image spacing must be positive and finite along every axis");
    }
  }
  const Eigen::Matrix3d gram = image.Direction.transpose() * image.Direction;
  if (!gram.isApprox(Eigen::Matrix3d::Identity(), 1e-6))
  {
    return Status::Error(
      "the image direction matrix is not orthonormal (sheared or scaled axes are not supported)");
  }
  std::array<int, 3> lower, upper;
  if (!TissueIndexBounds(image, lower, upper))
  {
    return Status::Error("the image has no tissue: every voxel holds a background label");
  }
  return Status::Ok();
}

void OrthonormalizeDirection(LabelImage& image)
{
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(
    image.Direction, Eigen::ComputeFullU | Eigen::ComputeFullV);
  image.Direction = svd.matrixU() * svd.matrixV().transpose();
}

namespace
{
// Whether any voxel of the box [from, to] (inclusive, within the stored box) is tissue.
bool AnyTissue(const LabelImage& image, const std::array<int, 3>& from, const std::array<int, 3>& to)
{
  for (int k = from[2]; k <= to[2]; ++k)
    for (int j = from[1]; j <= to[1]; ++j)
    {
      const std::int32_t* row = image.Labels.data() + image.VoxelIndex(from[0], j, k);
      for (int i = 0; i <= to[0] - from[0]; ++i)
        if (image.IsTissue(row[i]))
          return true;
    }
  return false;
}
} // namespace

bool TissueIndexBounds(const LabelImage& image, std::array<int, 3>& lower,
  std::array<int, 3>& upper)
{
  // Planes from each side of the stored box inwards, z, then y within the z range found, then x
  // within both: a stored box that fits its tissue closely (one voxel around it) costs a few
  // planes, not the whole box. Beyond the stored box every voxel is background.
  lower = image.StoredLower;
  upper = image.StoredUpper();
  for (int axis = 2; axis >= 0; --axis)
  {
    auto plane = [&](int index) {
      std::array<int, 3> from = lower, to = upper;
      from[axis] = to[axis] = index;
      return AnyTissue(image, from, to);
    };
    while (lower[axis] <= upper[axis] && !plane(lower[axis]))
      ++lower[axis];
    if (lower[axis] > upper[axis])
    {
      lower = image.Dimensions;
      upper = { -1, -1, -1 };
      return false;
    }
    while (!plane(upper[axis]))
      --upper[axis];
  }
  return true;
}
} // namespace cbc3d
