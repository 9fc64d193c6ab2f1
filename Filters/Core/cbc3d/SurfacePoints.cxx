#include "cbc3d/SurfacePoints.h"

#include "cbc3d/Parallel.h"
#include "cbc3d/TetTopology.h"

#include <algorithm>
#include <array>
#include <tuple>

namespace cbc3d
{
std::map<std::int32_t, std::vector<PointId>> TissueSurfaceVertices(const TetMesh& mesh)
{
  // Bucket every tet face by its smallest vertex (a counting sort, linear time), then find
  // within each small bucket the faces a tissue uses once.
  struct Face
  {
    PointId B, C; // the other two vertices, B < C
    std::int32_t Label;
    bool operator<(const Face& o) const { return std::tie(B, C, Label) < std::tie(o.B, o.C, o.Label); }
  };
  const std::size_t pointCount = mesh.Points.size();
  std::vector<std::size_t> start(pointCount + 1, 0);
  auto sortedFace = [&](std::size_t t, int f) {
    std::array<PointId, 3> ids = { mesh.Tets[t][TetFaces[f][0]], mesh.Tets[t][TetFaces[f][1]],
      mesh.Tets[t][TetFaces[f][2]] };
    std::sort(ids.begin(), ids.end());
    return ids;
  };
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    for (int f = 0; f < 4; ++f)
    {
      ++start[sortedFace(t, f)[0] + 1];
    }
  }
  for (std::size_t p = 0; p < pointCount; ++p)
  {
    start[p + 1] += start[p];
  }
  std::vector<Face> faces(start[pointCount]);
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    for (int f = 0; f < 4; ++f)
    {
      const auto ids = sortedFace(t, f);
      faces[fill[ids[0]]++] = Face{ ids[1], ids[2], mesh.Labels[t] };
    }
  }

  std::map<std::int32_t, std::vector<std::uint8_t>> onSurface;
  for (std::size_t a = 0; a < pointCount; ++a)
  {
    const auto first = faces.begin() + start[a];
    const auto last = faces.begin() + start[a + 1];
    std::sort(first, last);
    for (auto it = first; it != last;)
    {
      // A run of one face and one label: used once means a surface face of that tissue.
      auto next = it + 1;
      while (next != last && next->B == it->B && next->C == it->C && next->Label == it->Label)
      {
        ++next;
      }
      if (next - it == 1)
      {
        auto& marks = onSurface[it->Label];
        marks.resize(pointCount, 0);
        marks[a] = marks[it->B] = marks[it->C] = 1;
      }
      it = next;
    }
  }

  std::map<std::int32_t, std::vector<PointId>> result;
  for (const auto& [label, marks] : onSurface)
  {
    auto& ids = result[label];
    for (std::size_t p = 0; p < pointCount; ++p)
    {
      if (marks[p])
      {
        ids.push_back(static_cast<PointId>(p));
      }
    }
  }
  return result;
}

std::map<std::int32_t, std::vector<Eigen::Vector3d>> TissueBoundaryVoxelCentres(
  const LabelImage& image, int numberOfThreads)
{
  const auto& d = image.Dimensions;
  // One list of (label, voxel) per slice, merged in slice order for a thread-independent result.
  std::vector<std::vector<std::pair<std::int32_t, std::int64_t>>> perSlice(d[2]);
#pragma omp parallel for schedule(dynamic, 1) num_threads(ThreadCount(numberOfThreads))
  for (int k = 0; k < d[2]; ++k)
  {
    auto& found = perSlice[k];
    for (int j = 0; j < d[1]; ++j)
    {
      for (int i = 0; i < d[0]; ++i)
      {
        const std::int32_t label = image.LabelAt(i, j, k);
        if (!image.IsTissue(label))
        {
          continue;
        }
        const bool border = i == 0 || j == 0 || k == 0 || i == d[0] - 1 || j == d[1] - 1 || k == d[2] - 1;
        if (border || image.LabelAt(i - 1, j, k) != label || image.LabelAt(i + 1, j, k) != label ||
          image.LabelAt(i, j - 1, k) != label || image.LabelAt(i, j + 1, k) != label ||
          image.LabelAt(i, j, k - 1) != label || image.LabelAt(i, j, k + 1) != label)
        {
          found.emplace_back(label, image.VoxelIndex(i, j, k));
        }
      }
    }
  }
  std::map<std::int32_t, std::vector<Eigen::Vector3d>> result;
  for (const auto& slice : perSlice)
  {
    for (const auto& [label, voxel] : slice)
    {
      const std::int64_t i = voxel % d[0];
      const std::int64_t j = (voxel / d[0]) % d[1];
      const std::int64_t k = voxel / (std::int64_t(d[0]) * d[1]);
      result[label].push_back(image.IndexToWorld(Eigen::Vector3d(double(i), double(j), double(k))));
    }
  }
  return result;
}
} // namespace cbc3d
