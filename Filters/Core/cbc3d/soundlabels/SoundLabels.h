#ifndef cbc3d_SoundLabels_h
#define cbc3d_SoundLabels_h

// Stage: sound labels. Takes tets with their voxel counts and labels; gives labels with no tet
// hanging on an edge or a vertex, manifold tissue surfaces and no stray piece or cavity that
// the image lacks (this file). The manifold repair (ManifoldRepair.h, StarRepairer.h,
// VertexStar.h), the image's regions (ImageRegions.h) and stray components
// (StrayComponents.h) are its parts. Run by refinement after each pass.

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/sampling/TetVoxelSampler.h"
#include "cbc3d/sampling/TissueComponents.h"
#include "cbc3d/soundlabels/ImageRegions.h"

#include <array>
#include <cstdint>
#include <map>
#include <vector>

namespace cbc3d
{
struct SoundLabelsResult
{
  std::int64_t Relabelled = 0;  // tets whose label changed
  std::int64_t Repairs = 0;     // vertex stars mended
  std::int64_t StrayPieces = 0; // pieces that stood for no image component, given away
  std::int64_t Unrepaired = 0;  // vertices still not manifold (0 unless a work bound was hit)
};

/// Relabels the tets of a conforming mesh (every tet labelled, `background` for those outside
/// the image) so that it is a sound finite-element model: every tissue, the background and so
/// the body as a whole are manifold at every vertex (no hinge, no non-manifold edge or vertex
/// on any boundary or interface: see ManifoldRepair.h), and every face-connected piece of a
/// tissue or of the background stands for a 6-connected component of the image (`regions`,
/// FindImageRegions with the same `background`) of at least the minimum voxels, or a smaller one (a speck) where the piece lies against another
/// tissue rather than afloat in the background (other pieces: islands, cavities, the cut-off
/// ends of a pinch, are given to their neighbours: see StrayComponents.h), and no repair joins
/// background parts that stand for components the image keeps apart (a cavity and the outside:
/// see BackgroundRegionOfTets). Relabelling is by
/// voxel votes (`counts`); `across` is FaceNeighbours(tets); tets in `pinned` (tet -> label:
/// the tets that stand for a component refinement could not reach) keep their label unless
/// nothing else works. Returns what it did.
SoundLabelsResult MakeLabelsSound(const LabelImage& image, const ImageRegions& regions,
  const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets,
  const std::vector<TetNeighbours>& across,
  const std::vector<LabelCounts>& counts, const VoxelOwners& voxelOwner,
  const std::map<std::int64_t, std::int32_t>& pinned, std::int32_t background,
  std::vector<std::int32_t>& labels, int numberOfThreads = 1);
} // namespace cbc3d

#endif
