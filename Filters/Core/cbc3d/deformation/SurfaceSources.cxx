#include "cbc3d/deformation/SurfaceSources.h"

#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/TetTopology.h"

#include <algorithm>

namespace cbc3d
{
SurfaceSources FindSurfaceSources(const TetMesh& mesh)
{
  return FindSurfaceSources(mesh, FindMeshFaces(mesh));
}

SurfaceSources FindSurfaceSources(const TetMesh& mesh, const std::vector<MeshFace>& faces)
{
  const std::size_t n = mesh.Points.size();
  std::vector<char> onSurface(n, 0), outer(n, 0);
  for (const MeshFace& face : faces)
  {
    const bool boundary = face.TetCount == 1;
    const bool interface = face.TetCount == 2 && mesh.Labels[face.Tets[0]] != mesh.Labels[face.Tets[1]];
    for (const PointId p : face.Points)
    {
      onSurface[p] |= boundary || interface;
      outer[p] |= boundary;
    }
  }
  std::vector<LabelSet> labels(n);
  std::vector<double> length(n, 0.0);
  std::vector<int> edges(n, 0);
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const Tet& tet = mesh.Tets[t];
    for (const PointId p : tet)
    {
      if (onSurface[p] && std::find(labels[p].begin(), labels[p].end(), mesh.Labels[t]) == labels[p].end())
      {
        labels[p].push_back(mesh.Labels[t]);
      }
    }
    for (const auto& e : TetEdges)
    {
      const double l = (mesh.Points[tet[e[0]]] - mesh.Points[tet[e[1]]]).norm();
      length[tet[e[0]]] += l;
      length[tet[e[1]]] += l;
      ++edges[tet[e[0]]];
      ++edges[tet[e[1]]];
    }
  }
  SurfaceSources sources;
  sources.LocalSize.resize(n);
  for (std::size_t p = 0; p < n; ++p)
  {
    sources.LocalSize[p] = edges[p] ? length[p] / edges[p] : 0.0;
    if (onSurface[p])
    {
      if (outer[p])
      {
        labels[p].push_back(OutsideLabel);
      }
      std::sort(labels[p].begin(), labels[p].end());
      sources.Points.push_back(static_cast<PointId>(p));
      sources.Labels.push_back(labels[p]);
    }
  }
  return sources;
}
} // namespace cbc3d
