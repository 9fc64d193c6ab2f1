#ifndef cbc3d_StrayComponents_h
#define cbc3d_StrayComponents_h

#include "cbc3d/ManifoldRepair.h"
#include "cbc3d/TetVoxelSampler.h"
#include "cbc3d/TissueComponents.h"

#include <cstdint>
#include <vector>

namespace cbc3d
{
/// The image's components as the mesh should keep them: each voxel's component (-1 for none to
/// keep: too small, or the background on the image border, which the outside stands for) and
/// each component's class.
/// The tissue components are regions 0..n-1 and the kept cavities follow; the voxels' regions
/// are read from the components the image already has, not from a whole-image copy.
struct ImageRegions
{
  const TissueComponents* Tissues = nullptr;
  std::vector<std::int32_t> GapOfVoxel;  // background component per voxel, or -1; empty: none
  std::vector<std::int32_t> RegionOfGap; // per background component: its region, or -1
  std::vector<std::int32_t> ClassOfRegion;
  /// Per region: a speck (fewer voxels than a component must have to be kept for sure), which
  /// keeps its piece only where that piece lies against another tissue, not afloat.
  std::vector<char> Speck;
};

/// Gives away the face-connected pieces of a class (tissue or background) that stand for no
/// component of the image: a piece stands for an image component when it holds the most of its
/// voxels (`voxelOwner`: the tet owning each voxel centre, or -1), and, for a speck, when it
/// also touches another tissue (a speck afloat in the background would be a loose body); the
/// background's piece that reaches the mesh boundary is the outside and always stays. A piece given away goes tet by
/// tet, from its rim inwards, to the neighbouring class each tet holds most votes of. Appends
/// the tets relabelled to `changed`; returns how many pieces went.
std::int64_t RemoveStrayComponents(const std::vector<Tet>& tets,
  const std::vector<std::array<std::int64_t, 4>>& across, std::int32_t background,
  const ClassVotes& votes, const VoxelOwners& voxelOwner, const ImageRegions& regions,
  std::vector<std::int32_t>& classes, std::vector<std::int64_t>& changed);
/// Whether some face-connected piece of the background does not reach the mesh boundary (a
/// cavity, which only a cavity of the image may justify).
bool HasEnclosedBackground(const std::vector<Tet>& tets,
  const std::vector<std::array<std::int64_t, 4>>& across, std::int32_t background,
  const std::vector<std::int32_t>& classes);
} // namespace cbc3d

#endif
