#ifndef cbc3d_LabelImage_h
#define cbc3d_LabelImage_h

#include "cbc3d/LabelCodes.h"
#include "cbc3d/Status.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace cbc3d
{
/// A 3-D label map in its physical frame, the only way the core sees an image.
///
/// Voxel (i,j,k) has its centre at World = Origin + Direction * (Spacing .* (i,j,k)), the
/// convention of vtkImageData. Direction has orthonormal columns and may be a reflection.
/// Labels are stored x fastest. Every label that is not a background label is a tissue.
struct LabelImage
{
  std::array<int, 3> Dimensions = { 0, 0, 0 };
  Eigen::Vector3d Origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d Spacing = Eigen::Vector3d::Ones();
  Eigen::Matrix3d Direction = Eigen::Matrix3d::Identity();
  std::vector<std::int32_t> Labels;
  std::vector<std::int32_t> BackgroundLabels = { 0 };
  LabelCodes Codes; // the values the labels stand for (the labels themselves unless larger)

  std::int64_t VoxelCount() const
  {
    return std::int64_t(this->Dimensions[0]) * this->Dimensions[1] * this->Dimensions[2];
  }
  std::int64_t VoxelIndex(int i, int j, int k) const
  {
    return i + std::int64_t(this->Dimensions[0]) * (j + std::int64_t(this->Dimensions[1]) * k);
  }
  std::int32_t LabelAt(int i, int j, int k) const { return this->Labels[this->VoxelIndex(i, j, k)]; }
  bool IsBackground(std::int32_t label) const
  {
    // One background label is the common case: no loop for it.
    if (this->BackgroundLabels.size() == 1)
    {
      return label == this->BackgroundLabels[0];
    }
    for (const std::int32_t background : this->BackgroundLabels)
    {
      if (label == background)
      {
        return true;
      }
    }
    return false;
  }
  bool IsTissue(std::int32_t label) const { return !this->IsBackground(label); }

  /// Continuous index (i,j,k) to world, and back.
  Eigen::Vector3d IndexToWorld(const Eigen::Vector3d& index) const;
  /// The world-space centre of the voxel at a linear index (VoxelIndex's inverse, then world).
  Eigen::Vector3d VoxelCentre(std::int64_t voxel) const
  {
    const std::int64_t row = this->Dimensions[0], slice = row * this->Dimensions[1];
    return this->IndexToWorld(
      Eigen::Vector3d(double(voxel % row), double((voxel / row) % this->Dimensions[1]), double(voxel / slice)));
  }
  Eigen::Vector3d WorldToIndex(const Eigen::Vector3d& world) const;

  /// The tissue labels present in the image, sorted ascending.
  std::vector<std::int32_t> TissueLabels() const;
};

/// Checks that the image is a usable 3-D label map: at least 2 voxels along every axis,
/// positive spacing, an orthonormal direction, labels for every voxel, and one tissue voxel.
Status ValidateLabelImage(const LabelImage& image);

/// Replaces a nearly orthonormal direction (a file header stores it in float32) by the nearest
/// orthonormal matrix, so lattice angles come out exact. Reflections stay reflections.
void OrthonormalizeDirection(LabelImage& image);

/// Index-space box of the tissue voxels (inclusive); false when the image has no tissue.
bool TissueIndexBounds(const LabelImage& image, std::array<int, 3>& lower,
  std::array<int, 3>& upper);
} // namespace cbc3d

#endif
