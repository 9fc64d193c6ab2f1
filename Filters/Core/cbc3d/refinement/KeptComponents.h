#ifndef cbc3d_KeptComponents_h
#define cbc3d_KeptComponents_h

#include "cbc3d/refinement/LabelledMesh.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <map>
#include <vector>

namespace cbc3d
{
/// Whether a component is too small to be kept (fewer than `minimumVoxels` voxels).
inline bool IsSmall(const TissueComponents& components, std::int32_t component, int minimumVoxels)
{
  return components.Size[component] < minimumVoxels;
}

/// Gives each component still missing from the mesh the tet holding most of it, pins the tets
/// of components that few tets stand for, and makes the labels sound (refinement's SoundLabels),
/// in rounds until no component is lost again. Returns the fidelity measured last; adds the
/// tets the repair relabelled to `relabelled`.
std::map<std::int32_t, TissueFidelity> KeepComponentsAndMakeSound(const LabelImage& image,
  const TissueComponents& components, const RefinementParams& params,
  const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<std::int64_t, 4>>& across,
  LabelledMesh& mesh, std::vector<char>& componentInMesh, std::int64_t& relabelled);
} // namespace cbc3d

#endif
