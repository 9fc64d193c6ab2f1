#include "cbc3d/sampling/SurfacePoints.h"

#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/Parallel.h"

#include <algorithm>

namespace cbc3d
{
std::map<std::int32_t, std::vector<PointId>> TissueSurfaceVertices(const TetMesh& mesh)
{
  return TissueSurfaceVertices(mesh, FindMeshFaces(mesh));
}

std::map<std::int32_t, std::vector<PointId>> TissueSurfaceVertices(
  const TetMesh& mesh, const std::vector<MeshFace>& faces)
{
  // A face belongs to exactly one tet of a tissue when it is on the mesh boundary, or between
  // tets of two different tissues (an interface, on the surface of both).
  std::map<std::int32_t, std::vector<std::uint8_t>> onSurface;
  auto mark = [&](std::int32_t label, const MeshFace& face) {
    auto& marks = onSurface[label];
    marks.resize(mesh.Points.size(), 0);
    for (const PointId p : face.Points)
    {
      marks[p] = 1;
    }
  };
  for (const MeshFace& face : faces)
  {
    const std::int32_t first = mesh.Labels[face.Tets[0]];
    if (face.TetCount == 1)
    {
      mark(first, face);
    }
    else if (face.TetCount == 2 && mesh.Labels[face.Tets[1]] != first)
    {
      mark(first, face);
      mark(mesh.Labels[face.Tets[1]], face);
    }
  }
  std::map<std::int32_t, std::vector<PointId>> result;
  for (const auto& [label, marks] : onSurface)
  {
    auto& ids = result[label];
    for (std::size_t p = 0; p < marks.size(); ++p)
    {
      if (marks[p])
      {
        ids.push_back(static_cast<PointId>(p));
      }
    }
  }
  return result;
}

namespace
{
// Marks the voxels a..b of row (j, k) that do not hold `label` (marks[0] is voxel a), run by run.
void MarkOtherLabels(const LabelImage& image, int j, int k, int a, int b, std::int32_t label, std::vector<char>& marks)
{
  image.ForEachRun(j, k, a, b, [&](std::int32_t other, int length, int x) {
    if (other != label)
    {
      std::fill(marks.begin() + (x - a), marks.begin() + (x - a + length), 1);
    }
  });
}

// The boundary voxels of slice k as (label, voxel), in voxel order.
void AddSliceBoundaryVoxels(const LabelImage& image, int k, std::vector<char>& marks,
  std::vector<std::pair<std::int32_t, std::int64_t>>& found)
{
  const auto& d = image.Dimensions;
  const std::array<int, 3> first = image.StoredLower, last = image.StoredUpper();
  for (int j = first[1]; j <= last[1]; ++j)
  {
    // Run by run: the ends of a tissue run differ from their neighbours along x (or lie on
    // the image's border), and the rows around are read run by run too. Those rows are
    // stored for a tissue run unless it lies on the image's border, where all its voxels are
    // boundary voxels.
    const std::int64_t row = image.VoxelIndex(first[0], j, k) - first[0];
    const bool borderRow = j == 0 || k == 0 || j == d[1] - 1 || k == d[2] - 1;
    image.ForEachRun(j, k, first[0], last[0], [&](std::int32_t label, int length, int a) {
      const int b = a + length - 1;
      if (image.IsTissue(label))
      {
        marks.assign(static_cast<std::size_t>(length), borderRow ? 1 : 0);
        marks.front() = marks.back() = 1;
        if (!borderRow)
        {
          MarkOtherLabels(image, j - 1, k, a, b, label, marks);
          MarkOtherLabels(image, j + 1, k, a, b, label, marks);
          MarkOtherLabels(image, j, k - 1, a, b, label, marks);
          MarkOtherLabels(image, j, k + 1, a, b, label, marks);
        }
        for (int i = a; i <= b; ++i)
        {
          if (marks[i - a])
          {
            found.emplace_back(label, row + i);
          }
        }
      }
    });
  }
}
} // namespace

TissueVoxels TissueBoundaryVoxels(const LabelImage& image, int numberOfThreads)
{
  const auto& d = image.Dimensions;
  // Beyond the stored box there is no tissue, and one voxel around every tissue voxel is stored.
  const std::array<int, 3> first = image.StoredLower, last = image.StoredUpper();
  // One list of (label, voxel) per slice, merged in slice order for a thread-independent result.
  std::vector<std::vector<std::pair<std::int32_t, std::int64_t>>> perSlice(d[2]);
  RegionErrors errors; // the slices' lists grow
#pragma omp parallel num_threads(ThreadCount(numberOfThreads))
  {
    std::vector<char> marks;
#pragma omp for schedule(dynamic, 1)
    for (int k = first[2]; k <= last[2]; ++k)
      errors.Run([&] { AddSliceBoundaryVoxels(image, k, marks, perSlice[k]); });
  }
  errors.Rethrow();
  TissueVoxels result;
  for (const auto& slice : perSlice)
  {
    for (const auto& [label, voxel] : slice)
    {
      result[label].push_back(voxel);
    }
  }
  return result;
}

std::map<std::int32_t, std::vector<Eigen::Vector3d>> TissueBoundaryVoxelCentres(
  const LabelImage& image, int numberOfThreads)
{
  std::map<std::int32_t, std::vector<Eigen::Vector3d>> result;
  for (const auto& [label, voxels] : TissueBoundaryVoxels(image, numberOfThreads))
  {
    auto& centres = result[label];
    centres.reserve(voxels.size());
    for (const std::int64_t voxel : voxels)
    {
      centres.push_back(image.VoxelCentre(voxel));
    }
  }
  return result;
}
} // namespace cbc3d
