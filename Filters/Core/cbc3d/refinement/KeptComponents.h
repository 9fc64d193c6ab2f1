#ifndef cbc3d_KeptComponents_h
#define cbc3d_KeptComponents_h

#include "cbc3d/refinement/LabelledMesh.h"
#include "cbc3d/soundlabels/ImageRegions.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <map>
#include <vector>

namespace cbc3d
{
/// Rounds of making the labels sound, each after giving lost components their tets back.
constexpr int SoundLabelRounds = 3;

/// Whether a component is too small to be kept (fewer than `minimumVoxels` voxels).
inline bool IsSmall(const TissueComponents& components, std::int32_t component, int minimumVoxels)
{
  return components.Size[component] < minimumVoxels;
}

/// Gives each component still missing from the mesh the tet holding most of it, pins the tets
/// of components that few tets stand for, and makes the labels sound (refinement's SoundLabels,
/// against the image's `regions`), in rounds until no component is lost again. Returns the
/// fidelity measured last; adds the tets the repair relabelled to `relabelled`. Over ranks
/// (params.Ranks), the components are the whole image's and the choices are the same on every
/// rank.
std::map<std::int32_t, TissueFidelity> KeepComponentsAndMakeSound(const LabelImage& image,
  const TissueComponents& components, const ImageRegions* regions, const RefinementParams& params,
  const std::vector<Eigen::Vector3d>& points, const std::vector<TetNeighbours>& across,
  LabelledMesh& mesh, std::vector<char>& componentInMesh, std::int64_t& relabelled);
} // namespace cbc3d

#endif
