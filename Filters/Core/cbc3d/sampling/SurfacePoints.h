#ifndef cbc3d_SurfacePoints_h
#define cbc3d_SurfacePoints_h

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/TetMesh.h"

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <vector>

namespace cbc3d
{
/// The point sets between which the paper measures a tissue's Hausdorff distance.

/// Per tissue label, the ids of the mesh vertices on that tissue's surface: the vertices of the
/// faces that belong to exactly one tet of the tissue (outer boundary and interfaces alike; the
/// mesh must conform). Ids are ascending.
std::map<std::int32_t, std::vector<PointId>> TissueSurfaceVertices(const TetMesh& mesh);
/// The same from the mesh's faces (FindMeshFaces, or SurfaceFaces: faces inside a tissue are
/// ignored), when the caller has them already.
std::map<std::int32_t, std::vector<PointId>> TissueSurfaceVertices(
  const TetMesh& mesh, const std::vector<MeshFace>& faces);

/// Per tissue label, voxel indices (LabelImage::VoxelIndex), ascending.
using TissueVoxels = std::map<std::int32_t, std::vector<std::int64_t>>;

/// Per tissue label, the indices of the tissue's boundary voxels: voxels of the tissue with a
/// face-neighbour (6-neighbour) outside it, the image border counting as outside. Ascending,
/// the same for any thread count.
TissueVoxels TissueBoundaryVoxels(const LabelImage& image, int numberOfThreads = 0);

/// The world-space centres of TissueBoundaryVoxels, in the same order.
std::map<std::int32_t, std::vector<Eigen::Vector3d>> TissueBoundaryVoxelCentres(
  const LabelImage& image, int numberOfThreads = 0);
} // namespace cbc3d

#endif
