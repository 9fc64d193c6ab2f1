#include "cbc3d/SurfacePoints.h"

#include "cbc3d/MeshFaces.h"
#include "cbc3d/Parallel.h"

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

TissueVoxels TissueBoundaryVoxels(const LabelImage& image, int numberOfThreads)
{
  const auto& d = image.Dimensions;
  // Beyond the stored box there is no tissue, and one voxel around every tissue voxel is stored.
  const std::array<int, 3> first = image.StoredLower, last = image.StoredUpper();
  // One list of (label, voxel) per slice, merged in slice order for a thread-independent result.
  std::vector<std::vector<std::pair<std::int32_t, std::int64_t>>> perSlice(d[2]);
  const std::array<std::int64_t, 3> stride = image.VoxelStrides();
  const std::int32_t* labels = image.Labels.data();
#pragma omp parallel for schedule(dynamic, 1) num_threads(ThreadCount(numberOfThreads))
  for (int k = first[2]; k <= last[2]; ++k)
  {
    auto& found = perSlice[k];
    for (int j = first[1]; j <= last[1]; ++j)
    {
      // Indices, not pointers, into the rows around: those beyond the stored box are only
      // read for tissue voxels, which are never at its edge unless at the image's border.
      const std::int64_t row = image.VoxelIndex(first[0], j, k) - first[0];
      const bool borderRow = j == 0 || k == 0 || j == d[1] - 1 || k == d[2] - 1;
      for (int i = first[0]; i <= last[0]; ++i)
      {
        const std::int64_t v = row + i;
        const std::int32_t label = labels[v];
        if (!image.IsTissue(label))
        {
          continue;
        }
        if (borderRow || i == 0 || i == d[0] - 1 || labels[v - 1] != label || labels[v + 1] != label ||
          labels[v - stride[1]] != label || labels[v + stride[1]] != label ||
          labels[v - stride[2]] != label || labels[v + stride[2]] != label)
        {
          found.emplace_back(label, v);
        }
      }
    }
  }
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
