#ifndef cbc3d_SurfaceSources_h
#define cbc3d_SurfaceSources_h

#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/deformation/BoundaryTargets.h"

#include <vector>

namespace cbc3d
{
/// The deformation's sources: surface and interface vertices with their label-sets, and every vertex's element size.
struct SurfaceSources
{
  std::vector<PointId> Points;
  std::vector<LabelSet> Labels;
  std::vector<double> LocalSize; // per mesh point: mean length of the edges at it
};

/// The mesh's surface and interface vertices, each with the labels of its tets (plus
/// OutsideLabel on the outer surface), and every vertex's element size.
SurfaceSources FindSurfaceSources(const TetMesh& mesh);
/// The same from the mesh's faces (FindMeshFaces, or SurfaceFaces: faces inside a tissue are
/// ignored), when the caller has them already.
SurfaceSources FindSurfaceSources(const TetMesh& mesh, const std::vector<MeshFace>& faces);
} // namespace cbc3d

#endif
