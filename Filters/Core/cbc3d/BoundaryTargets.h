#ifndef cbc3d_BoundaryTargets_h
#define cbc3d_BoundaryTargets_h

#include "cbc3d/LabelImage.h"

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

struct BoundaryTarget
{
  Eigen::Vector3d Position; // the voxel centre, world
  LabelSet Labels;          // its label and its face-neighbours' (OutsideLabel for background)
};

/// The registration targets: centres of tissue voxels with a face-neighbour of another label
/// (the image border counts as outside). Tissues are scanned in ascending label order, each
/// in x-fastest order; a target whose label-set an earlier tissue already produced is skipped,
/// so each interface is sampled from one side. After a voxel is taken, its neighbours under the
/// pattern are not taken.
std::vector<BoundaryTarget> FindBoundaryTargets(const LabelImage& image, TargetPattern pattern);
} // namespace cbc3d

#endif
