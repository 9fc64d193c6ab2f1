#include "cbc3d/SurfaceEars.h"

#include "cbc3d/MeshFaces.h"

#include <algorithm>

namespace cbc3d
{
std::size_t RemoveSurfaceEars(const std::vector<Tet>& tets, std::size_t pointCount,
  std::vector<std::int32_t>& labels, const std::function<bool(std::int32_t)>& isTissue,
  std::int32_t removed)
{
  // The tets on each face, looked up by the face's ascending vertices.
  std::vector<MeshFace> faces = FindMeshFaces(tets, pointCount);
  std::sort(faces.begin(), faces.end(), [](const MeshFace& a, const MeshFace& b) { return a.Points < b.Points; });
  std::size_t relabelled = 0;
  for (bool changed = true; changed;)
  {
    changed = false;
    std::vector<int> uses(pointCount, 0);
    for (std::size_t t = 0; t < tets.size(); ++t)
      if (isTissue(labels[t]))
        for (const PointId p : tets[t])
          ++uses[p];
    for (std::size_t t = 0; t < tets.size(); ++t)
    {
      if (!isTissue(labels[t]))
      {
        continue;
      }
      for (int tip = 0; tip < 4; ++tip)
      {
        if (uses[tets[t][tip]] != 1)
        {
          continue;
        }
        std::array<PointId, 3> base;
        for (int v = 0, b = 0; v < 4; ++v)
          if (v != tip)
            base[b++] = tets[t][v];
        std::sort(base.begin(), base.end());
        const auto& pair = std::lower_bound(faces.begin(), faces.end(), base,
          [](const MeshFace& face, const std::array<PointId, 3>& points) { return face.Points < points; })->Tets;
        const std::int64_t other = pair[0] == std::int64_t(t) ? pair[1] : pair[0];
        if (other >= 0 && labels[other] == labels[t])
        {
          labels[t] = removed;
          for (const PointId p : tets[t])
            --uses[p];
          ++relabelled;
          changed = true;
          break;
        }
      }
    }
  }
  return relabelled;
}
} // namespace cbc3d
