#ifndef cbc3d_LabelledMesh_h
#define cbc3d_LabelledMesh_h

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/lattice/RedGreenMesh.h"
#include "cbc3d/refinement/Refinement.h"
#include "cbc3d/sampling/TetVoxelSampler.h"
#include "cbc3d/sampling/TissueComponents.h"

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <vector>

#include "cbc3d/refinement/RankPasses.h"

namespace cbc3d
{
// A tet that holds no sample at all (outside the image) has no label.
constexpr std::int32_t NoLabel = std::numeric_limits<std::int32_t>::min();

/// Whether a pass's label is a tissue of the image (not NoLabel, not background).
inline bool IsTissueLabel(const LabelImage& image, std::int32_t label)
{
  return label != NoLabel && image.IsTissue(label);
}

// One pass's view of the conforming mesh: tets, their red leaves, samples and labels.
struct LabelledMesh
{
  std::vector<Tet> Tets;
  std::vector<std::int64_t> Source;
  std::vector<LabelCounts> Counts;
  std::vector<char> HoldsVoxelCentres; // counts are whole voxels (else sub-samples)
  std::vector<std::int32_t> Labels;

  // The tet owning each voxel centre, as an owner id (-1: none), and the tet of each id. Ids
  // outlive passes: a tet that a pass leaves as it was keeps its id and its voxels' entries,
  // so only the voxels of new tets are written again.
  VoxelOwners VoxelOwner;
  std::vector<std::int32_t> OwnerTet;
  std::int32_t OwnerOf(std::int64_t voxel) const
  {
    const std::int32_t id = this->VoxelOwner[voxel];
    return id < 0 ? -1 : this->OwnerTet[id];
  }

  // What the last pass sampled, per red: its split mask as a leaf (RedGreenMesh::NotLeaf if
  // none), its first tet and that tet's owner id. A leaf with the same mask makes the same
  // tets, whose samples are taken over.
  std::vector<std::uint8_t> LeafMask;
  std::vector<std::int64_t> FirstTet;
  std::vector<std::int32_t> FirstOwner;
};

/// Takes the conforming mesh of `hierarchy` into `mesh`, with each tet's samples and label
/// (samples of tets the last pass made alike are taken over). Returns false when `keepGoing`
/// (polled from thread 0) asked to stop.
bool SampleAll(const LabelImage& image, const RedGreenMesh& hierarchy, int threads,
  LabelledMesh& mesh, const std::function<bool()>& keepGoing);

/// After the passes: every voxel's owner as its tet, and each tet its own id.
void ResolveOwners(LabelledMesh& mesh, int threads);

/// The tets whose centres lie in this rank's slab: the ones it keeps.
std::vector<char> RankOwnedTets(const LabelImage& image, const std::vector<Eigen::Vector3d>& points,
  const std::vector<Tet>& tets, const RankPasses& ranks);

/// F1 and F2 of every tissue, and which of its components (of `minimumVoxels` or more) have a
/// voxel in a tet of their label (`componentInMesh`, per component). With `ranks` (and the
/// mesh's `points`), F1 and F2 count this rank's slab and are summed over the ranks, and a
/// component is in the mesh where a voxel of the whole component in any rank's slab is.
std::map<std::int32_t, TissueFidelity> MeasureFidelity(const LabelImage& image,
  const TissueComponents& components, int minimumVoxels, const LabelledMesh& mesh, int threads,
  std::vector<char>& componentInMesh, const RankPasses* ranks = nullptr,
  const std::vector<Eigen::Vector3d>* points = nullptr);
} // namespace cbc3d

#endif
