#ifndef cbc3d_BoundaryTargets_h
#define cbc3d_BoundaryTargets_h

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/sampling/SurfacePoints.h"

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <vector>

namespace cbc3d
{
/// The label that stands for everything outside the tissues (background and beyond the image)
/// in label-sets.
constexpr std::int32_t OutsideLabel = std::numeric_limits<std::int32_t>::min();

/// A sorted set of labels, OutsideLabel first when present.
using LabelSet = std::vector<std::int32_t>;

/// Which neighbours of a taken target voxel may not be taken (the paper's non-connectivity
/// patterns): those sharing a vertex (26), an edge (18) or a face (6) with it, or none.
enum class TargetPattern
{
  Vertex,
  Edge,
  Face,
  None
};

/// Where a target sits in its voxel: at the centre (the paper's, and the points its Hausdorff
/// distance measures to), or moved half a voxel towards its face-neighbours of other labels,
/// onto the label boundary itself (meshes then keep their tissues' volumes; see
/// FindBoundaryTargets).
enum class TargetPlacement
{
  VoxelCentre,
  VoxelFace
};

struct BoundaryTarget
{
  Eigen::Vector3d Position; // world: the voxel centre, or the label boundary by it
  LabelSet Labels;          // its label and its face-neighbours' (OutsideLabel for background)
};

/// Where the target of a boundary voxel (a linear voxel index) sits, in world coordinates: its
/// centre, or with VoxelFace placement the centre moved by half the mean of the unit steps to
/// its face-neighbours of other labels (the image border counting as other): onto the shared
/// face when there is one such neighbour.
Eigen::Vector3d TargetPosition(const LabelImage& image, std::int64_t voxel, TargetPlacement placement);

/// The registration targets: centres of tissue voxels with a face-neighbour of another label
/// (the image border counts as outside). Tissues are scanned in ascending label order, each
/// in x-fastest order; a target whose label-set an earlier tissue already produced is skipped,
/// so each interface is sampled from one side. After a voxel is taken, its neighbours under the
/// pattern are not taken. Each sits at TargetPosition.
/// A slab of boundary voxels: those whose centres c have Lower <= Normal . c <= Upper.
struct BoundaryWindow
{
  bool Set = false;
  Eigen::Vector3d Normal = Eigen::Vector3d::UnitZ();
  double Lower = 0.0, Upper = 0.0;
};

/// The boundary voxels inside the window (all of them where it is not set).
TissueVoxels WithinWindow(const LabelImage& image, TissueVoxels boundary, const BoundaryWindow& window);

std::vector<BoundaryTarget> FindBoundaryTargets(const LabelImage& image, TargetPattern pattern,
  TargetPlacement placement = TargetPlacement::VoxelCentre);

/// The same from the tissues' boundary voxels, found already (TissueBoundaryVoxels): only
/// those voxels are looked at.
std::vector<BoundaryTarget> FindBoundaryTargets(const LabelImage& image, const TissueVoxels& boundary,
  TargetPattern pattern, TargetPlacement placement);
} // namespace cbc3d

#endif
