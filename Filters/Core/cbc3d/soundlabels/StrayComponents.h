#ifndef cbc3d_StrayComponents_h
#define cbc3d_StrayComponents_h

#include "cbc3d/soundlabels/ImageRegions.h"
#include "cbc3d/soundlabels/ManifoldRepair.h"

#include <cstdint>
#include <vector>

namespace cbc3d
{
/// Gives away the face-connected pieces of a class (tissue or background) that stand for no
/// component of the image: a piece stands for an image component when it holds the most of its
/// voxels (`voxelOwner`: the tet owning each voxel centre, or -1), and, for a speck, when it
/// also touches another tissue (a speck afloat in the background would be a loose body); the
/// background's piece that reaches the mesh boundary is the outside and always stays. A piece given away goes tet by
/// tet, from its rim inwards, to the neighbouring class each tet holds most votes of. Appends
/// the tets relabelled to `changed`; returns how many pieces went.
std::int64_t RemoveStrayComponents(const std::vector<Tet>& tets,
  const std::vector<TetNeighbours>& across, std::int32_t background,
  const ClassVotes& votes, const VoxelOwners& voxelOwner, const ImageRegions& regions,
  std::vector<std::int32_t>& classes, std::vector<std::int64_t>& changed);
} // namespace cbc3d

#endif
