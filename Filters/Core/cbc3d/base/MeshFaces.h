#ifndef cbc3d_MeshFaces_h
#define cbc3d_MeshFaces_h

#include "cbc3d/base/TetMesh.h"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace cbc3d
{
/// A face of a conforming tet mesh and the one or two tets that use it.
struct MeshFace
{
  std::array<PointId, 3> Points; // ascending
  std::array<std::int64_t, 2> Tets = { -1, -1 };
  int TetCount = 0; // 1: on the mesh boundary; 2: inside; more: the mesh does not conform
};

/// Every distinct face of tets over points 0..pointCount-1 (grouped in linear time by bucketing
/// on the smallest vertex), in ascending vertex order; the same list for any number of threads
/// (0 = all cores).
std::vector<MeshFace> FindMeshFaces(const std::vector<Tet>& tets, std::size_t pointCount, int numberOfThreads = 1);

/// The faces for which `keep` holds, in FindMeshFaces' order, found on the threads without
/// keeping every face: for callers that want a few of the faces of a large mesh. `keep` is
/// called twice a face, from several threads at once.
std::vector<MeshFace> SelectMeshFaces(const std::vector<Tet>& tets, std::size_t pointCount, int numberOfThreads,
  const std::function<bool(const MeshFace&)>& keep);

/// SelectMeshFaces over the tets in `subset` alone (ids in `tets`, ascending): a face is theirs
/// when one of them uses it, and names those tets by their ids in `tets`.
std::vector<MeshFace> SelectMeshFaces(const std::vector<Tet>& tets, const std::vector<std::int32_t>& subset,
  std::size_t pointCount, int numberOfThreads, const std::function<bool(const MeshFace&)>& keep);

/// The faces of a labelled mesh that bound a label: on the mesh boundary, between two labels,
/// or (a mesh that does not conform) shared by more than two tets; in FindMeshFaces' order.
/// Most faces are inside a tissue: those who want the surfaces alone need not hold them.
std::vector<MeshFace> SurfaceFaces(const TetMesh& mesh, int numberOfThreads = 1);

/// The tets across each tet's faces in a conforming mesh: Across[t][i] is the tet sharing the
/// face opposite local vertex i of tet t, or -1 on the mesh boundary.
std::vector<TetNeighbours> FaceNeighbours(
  const std::vector<Tet>& tets, std::size_t pointCount, int numberOfThreads = 1);

/// Every distinct face of the mesh.
inline std::vector<MeshFace> FindMeshFaces(const TetMesh& mesh, int numberOfThreads = 1)
{
  return FindMeshFaces(mesh.Tets, mesh.Points.size(), numberOfThreads);
}
} // namespace cbc3d

#endif
