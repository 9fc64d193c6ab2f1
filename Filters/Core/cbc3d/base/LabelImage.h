#ifndef cbc3d_LabelImage_h
#define cbc3d_LabelImage_h

#include "cbc3d/base/LabelCodes.h"
#include "cbc3d/base/Status.h"
#include "cbc3d/base/UninitializedVector.h"

#include <Eigen/Core>

#include <algorithm>
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
///
/// Labels may hold only a box of the image (StoredLower, StoredSize voxels per axis): then every
/// voxel beyond the box holds BackgroundLabels.front(), and voxel indices (VoxelIndex, and the
/// maps indexed like the labels) count within the box, so a padded image costs what its box
/// does. A StoredSize of zeros (the default) stores the whole image.
struct LabelImage
{
  std::array<int, 3> Dimensions = { 0, 0, 0 };
  Eigen::Vector3d Origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d Spacing = Eigen::Vector3d::Ones();
  Eigen::Matrix3d Direction = Eigen::Matrix3d::Identity();
  UninitializedVector<std::int32_t> Labels; // resize leaves new labels unset: fill them
  std::vector<std::int32_t> BackgroundLabels = { 0 };
  LabelCodes Codes; // the values the labels stand for (the labels themselves unless larger)
  std::array<int, 3> StoredLower = { 0, 0, 0 };
  std::array<int, 3> StoredSize = { 0, 0, 0 };
  /// A piece of a larger image (an MPI rank's slab) frames its lattice on the whole image's
  /// tissue box, given here in this image's voxel indices (it may reach beyond Dimensions), so
  /// that every piece's lattice is a part of the one lattice of the whole image. Unset, the
  /// lattice frames this image's own tissue box.
  bool HasLatticeBox = false;
  std::array<int, 3> LatticeBoxLower = { 0, 0, 0 };
  std::array<int, 3> LatticeBoxUpper = { -1, -1, -1 };
  /// Optional (IndexLabelRuns fills it; empty otherwise): each stored row's runs of one label.
  /// Row r = (j - StoredLower[1]) + StoredSize[1] * (k - StoredLower[2]) has the runs
  /// RowRunFirst[r] .. RowRunFirst[r + 1] - 1, each starting at x offset (from StoredLower[0])
  /// RunStart and holding RunLabel: counting a row's labels then reads neither its uniform
  /// stretches nor, on a large image, the cache lines of the labels. Whoever changes Labels
  /// afterwards clears the three.
  std::vector<std::int64_t> RowRunFirst;
  std::vector<std::int32_t> RunStart;
  std::vector<std::int32_t> RunLabel;

  std::int64_t VoxelCount() const
  {
    return std::int64_t(this->Dimensions[0]) * this->Dimensions[1] * this->Dimensions[2];
  }
  /// The voxels along each axis that Labels holds.
  const std::array<int, 3>& StoredDimensions() const
  {
    return this->StoredSize[0] > 0 ? this->StoredSize : this->Dimensions;
  }
  /// The last stored voxel along each axis (inclusive).
  std::array<int, 3> StoredUpper() const
  {
    const auto& n = this->StoredDimensions();
    return { this->StoredLower[0] + n[0] - 1, this->StoredLower[1] + n[1] - 1, this->StoredLower[2] + n[2] - 1 };
  }
  bool IsStored(int i, int j, int k) const
  {
    const auto& n = this->StoredDimensions();
    const auto& l = this->StoredLower;
    return unsigned(i - l[0]) < unsigned(n[0]) && unsigned(j - l[1]) < unsigned(n[1]) &&
      unsigned(k - l[2]) < unsigned(n[2]);
  }
  /// The index of a stored voxel (i,j,k) in Labels; +1 along x, the second stride along y, the
  /// third along z.
  std::int64_t VoxelIndex(int i, int j, int k) const
  {
    const auto& n = this->StoredDimensions();
    const auto& l = this->StoredLower;
    return (i - l[0]) + std::int64_t(n[0]) * ((j - l[1]) + std::int64_t(n[1]) * (k - l[2]));
  }
  std::array<std::int64_t, 3> VoxelStrides() const
  {
    const auto& n = this->StoredDimensions();
    return { 1, n[0], std::int64_t(n[0]) * n[1] };
  }
  /// VoxelIndex's inverse.
  std::array<int, 3> VoxelCoordinates(std::int64_t voxel) const
  {
    const auto& n = this->StoredDimensions();
    const std::int64_t row = n[0], slice = row * n[1];
    return { int(voxel % row) + this->StoredLower[0], int((voxel / row) % n[1]) + this->StoredLower[1],
      int(voxel / slice) + this->StoredLower[2] };
  }
  /// The label of a stored voxel.
  std::int32_t LabelAt(int i, int j, int k) const { return this->Labels[this->VoxelIndex(i, j, k)]; }
  /// The label of any voxel of the image: beyond the stored box, the first background label.
  std::int32_t LabelOf(int i, int j, int k) const
  {
    return this->IsStored(i, j, k) ? this->LabelAt(i, j, k) : this->BackgroundLabels.front();
  }
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
    const std::array<int, 3> at = this->VoxelCoordinates(voxel);
    return this->IndexToWorld(Eigen::Vector3d(double(at[0]), double(at[1]), double(at[2])));
  }
  Eigen::Vector3d WorldToIndex(const Eigen::Vector3d& world) const;

  /// Calls visit(label, voxels, x) for each run of one label among the stored voxels
  /// first..last (x, inclusive, within the stored box) of stored row (j, k): maximal runs, in
  /// order; x is the run's first voxel.
  template <typename Visit>
  void ForEachRun(int j, int k, int first, int last, Visit&& visit) const
  {
    const std::int32_t* row = this->Labels.data() + this->VoxelIndex(this->StoredLower[0], j, k);
    const int from = first - this->StoredLower[0], to = last - this->StoredLower[0];
    if (this->RowRunFirst.empty())
    {
      for (int start = from; start <= to;)
      {
        int end = start + 1;
        while (end <= to && row[end] == row[start])
          ++end;
        visit(row[start], end - start, start + this->StoredLower[0]);
        start = end;
      }
      return;
    }
    const std::int64_t r = (j - this->StoredLower[1]) +
      std::int64_t(this->StoredDimensions()[1]) * (k - this->StoredLower[2]);
    const std::int32_t* starts = this->RunStart.data();
    const std::int32_t* end = starts + this->RowRunFirst[r + 1];
    // The run holding `from`: the last one that starts at or before it (the first starts at 0).
    std::int64_t run = std::upper_bound(starts + this->RowRunFirst[r], end, from) - starts - 1;
    for (int start = from; start <= to; ++run)
    {
      const int next = starts + run + 1 < end ? std::min(starts[run + 1], to + 1) : to + 1;
      visit(this->RunLabel[run], next - start, start + this->StoredLower[0]);
      start = next;
    }
  }

  /// The tissue labels present in the image, sorted ascending.
  std::vector<std::int32_t> TissueLabels() const;
};

/// Fills RowRunFirst, RunStart and RunLabel from Labels (one pass over them, in parallel).
void IndexLabelRuns(LabelImage& image, int numberOfThreads = 0);

/// Checks that the image is a usable 3-D label map: at least 2 voxels along every axis,
/// positive spacing, an orthonormal direction, labels for every stored voxel of a stored box
/// within the image, and one tissue voxel.
Status ValidateLabelImage(const LabelImage& image);

/// Replaces a nearly orthonormal direction (a file header stores it in float32) by the nearest
/// orthonormal matrix, so lattice angles come out exact. Reflections stay reflections.
void OrthonormalizeDirection(LabelImage& image);

/// Index-space box of the tissue voxels (inclusive); false when the image has no tissue. Scans
/// the stored box only.
bool TissueIndexBounds(const LabelImage& image, std::array<int, 3>& lower,
  std::array<int, 3>& upper);
} // namespace cbc3d

#endif
