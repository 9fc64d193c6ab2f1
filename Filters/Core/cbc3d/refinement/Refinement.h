#ifndef cbc3d_Refinement_h
#define cbc3d_Refinement_h

// Stage: refinement. Takes a label image and the BCC lattice; gives the red-green refined,
// conforming mesh with a tissue label per tet, refined where voxel fidelity or the boundary's
// distance to the surface vertices (BoundaryCoverage.h) asks for it. Each pass samples the
// voxels (LabelledMesh.h), then keeps the tissues' components and makes the labels sound
// (KeptComponents.h).

#include "cbc3d/base/EdgeLengthLimits.h"
#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/Progress.h"
#include "cbc3d/base/Status.h"
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/refinement/RankPasses.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace cbc3d
{
struct RefinementParams
{
  /// Target F in [0, 1] for both voxel ratios F1 and F2 of every tissue (the paper's F).
  double Fidelity = 0.95;
  /// Targets of single tissues (label -> F in [0, 1]), in place of Fidelity for those tissues.
  std::map<std::int32_t, double> FidelityByTissue;
  /// No tet of a tissue keeps an edge longer than its limit at the end of refinement.
  EdgeLengthLimits MaximumEdge;
  /// The depth limit: a red split must leave edges at least this long (mm); 0 = the voxel
  /// size, the cube root of the voxel volume (so refinement stops when the finest edges reach
  /// the voxels, whatever their aspect). Splits for an edge limit obey only a floor given here.
  double MinimumEdgeLength = 0.0;
  /// Every 6-connected component of a tissue with at least this many voxels keeps tets of
  /// that tissue (thin vessels are refined towards, or kept by relabelling, never eroded).
  int MinimumComponentVoxels = 8;
  /// Every boundary voxel of a tissue (of a component that is kept) should end within this
  /// distance (mm) of a vertex of the tissue's surface, the measure of the paper's Hausdorff
  /// distance: where the surface after deformation (predicted) would leave voxels farther, the
  /// longest edge of the nearest surface face is split; and a tet with a surface vertex too far
  /// from every boundary voxel of its tissue to reach it is split red. 0 = automatic: 3/8 of the
  /// longest edge of the mesh to refine (3 mm for an 8 mm BCC lattice); negative = no such bound.
  double BoundaryDistance = 0.0;
  /// Relabel tets at the end so that the mesh is a sound FE model (no hinge, manifold tissue
  /// surfaces, no piece the image lacks, no cavity opened: see SoundLabels.h, and the ring of
  /// background tets, AddBackgroundRing, added first); false leaves the majority labels.
  bool SoundLabels = true;
  /// At most this many tets in the output (0 = no budget): each pass keeps the splits that fit,
  /// those that gain the most fidelity first (edge limits before all).
  std::int64_t MaximumTets = 0;
  /// OpenMP threads; 0 = all cores.
  int NumberOfThreads = 0;
  /// Stop refining before the mesh would need more memory than this (bytes); 0 = half the machine.
  std::size_t MemoryLimitBytes = 0;
  /// Over MPI ranks: the decisions every rank's passes share (RankPasses.h); null on one process.
  std::shared_ptr<const RankPasses> Ranks;

  /// The fidelity target of a tissue.
  double FidelityOf(std::int32_t label) const
  {
    const auto found = this->FidelityByTissue.find(label);
    return found == this->FidelityByTissue.end() ? this->Fidelity : found->second;
  }
  /// Whether any target asks for refinement: a fidelity above 0 or an edge limit.
  bool AsksForRefinement() const;
};

/// The voxel fidelity of one tissue: S1 = voxels in the tets labelled with it, S2 = its voxels,
/// F1 = |S1 n S2| / |S1|, F2 = |S1 n S2| / |S2|; and its 6-connected components (of at least
/// MinimumComponentVoxels voxels) in the image and how many have tets of the tissue.
struct TissueFidelity
{
  std::int32_t Label = 0;
  double F1 = 0.0;
  double F2 = 0.0;
  std::int64_t Components = 0;
  std::int64_t ComponentsInMesh = 0;
};

struct RefinementResult
{
  std::vector<TissueFidelity> Tissues; // ascending label
  double BoundaryDistance = 0.0;       // the bound used (mm); 0 when none
  double LargestBoundaryGap = 0.0;     // farthest boundary voxel from the predicted surface (mm)
  int Passes = 0;                      // refinement passes that split tets
  int DeepestLevel = 0;                // red level of the finest tets
  std::int64_t Relabelled = 0;         // tets relabelled for a sound mesh (see SoundLabels.h)
  std::vector<std::uint8_t> Levels;    // red level of every output tet
  std::string StopReason;              // why refinement ended, in words
  std::size_t OverlongTets = 0;        // tissue tets with an edge beyond their limit (mm)
};

/// Red-green refinement of a tet mesh (normally the BCC lattice) driven by voxel fidelity
/// (paper, section 3.2). Each pass labels every tet with the majority label of its voxels
/// (sampled finer where a tet holds no voxel centre; ties go to a tissue over background, then
/// to the smaller label), measures F1 and F2 per tissue, red-splits the tets that cross the
/// boundary of a tissue below the target, and splits where the surface would stay far from the
/// image boundary (BoundaryDistance), until every tissue reaches both, or no tet may be split
/// (MinimumEdgeLength), or memory would run out. A
/// tissue component the labelling misses is refined towards, then given the tet that holds
/// most of it. Tets labelled background are dropped. The result is conforming (no hanging
/// vertex), every tet positively oriented, and the same for any thread count.
Status RefineMesh(const LabelImage& image, const TetMesh& lattice, const RefinementParams& params,
  TetMesh& out, RefinementResult& result, const Progress& progress = nullptr);

/// The automatic MinimumEdgeLength (0): the voxel size, the cube root of the voxel volume.
inline double DefaultMinimumEdgeLength(const Eigen::Vector3d& spacing)
{
  return std::cbrt(spacing.prod());
}

/// The automatic BoundaryDistance (0): 3/8 of the longest edge of the mesh to refine.
inline double DefaultBoundaryDistance(double longestEdge)
{
  return 0.375 * longestEdge;
}
} // namespace cbc3d

#endif
