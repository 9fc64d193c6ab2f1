#ifndef cbc3d_Deformation_h
#define cbc3d_Deformation_h

// Stage: deformation. Takes the refined mesh and its label image; moves the tissue surfaces onto
// the image boundaries: targets on the boundaries (BoundaryTargets.h, Matcher.h,
// SurfaceSources.h), an elastic solve (LinearElasticity.h, ElasticStep.h), steps kept by the
// angle and fidelity guards (GuardedStep.h, FidelityGuard.h), interior smoothing, and the
// tissues' volumes restored (TissueVolumes.h, VolumeAims.h).

#include "cbc3d/base/EdgeLengthLimits.h"
#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/Progress.h"
#include "cbc3d/base/Status.h"
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/deformation/BoundaryTargets.h"
#include "cbc3d/deformation/LinearElasticity.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace cbc3d
{
struct DeformationParams
{
  /// Registration iterations (the paper's 5); 0 leaves the mesh as it is.
  int Iterations = 5;
  /// Target-point thinning (the paper's non-connectivity pattern).
  TargetPattern Pattern = TargetPattern::Edge;
  /// Targets on the label boundary (the default: tissues keep their volumes, brain 97.2% ->
  /// 98.7% at the paper's settings) or at boundary voxel centres (the paper's; the points its
  /// Hausdorff distance measures to). Steered vertices head for centres either way.
  TargetPlacement Placement = TargetPlacement::VoxelFace;
  /// Spring stiffness pulling each surface vertex to its target, as a multiple of the
  /// vertex's own diagonal stiffness: larger follows the image more closely.
  double Penalty = 10.0;
  /// No step may leave a tet with a dihedral angle under this (degrees) or over 180 minus it:
  /// vertices of such tets keep their place for that step (inverted tets are never made).
  double MinimumDihedralAngle = 20.0;
  /// Each iteration first moves the whole mesh by the rotation and translation that best fit
  /// the matches (least squares), matching again and fitting again until the fit settles, then
  /// deforms it elastically for the rest: a rigid move strains no tet, so a mesh shifted from
  /// its image follows it whole.
  bool RigidAlignment = true;
  /// After the iterations, every interface moves along its normals until each tissue holds its
  /// voxels' volume (TissueVolumeKeeper), as far as the angle and Hausdorff guards let it: a
  /// surface inscribed in a thin or curved boundary loses the volume between its faces and the
  /// boundary (the ventricles kept 92.4% of their voxels' volume without this, 100.0% with it).
  bool KeepVolumes = true;
  /// No step may stretch a tissue tet's edge past its limit (or past its length at the start,
  /// where that is longer): the limits refinement met hold after deformation.
  EdgeLengthLimits MaximumEdge;
  /// Materials per tissue label; others get DefaultMaterial.
  std::map<std::int32_t, Material> Materials;
  Material DefaultMaterial;
  /// OpenMP threads; 0 = all cores.
  int NumberOfThreads = 0;
  /// Points that keep their place (one flag per point; empty: none), where another process
  /// moves them: the mesh is one piece of a larger one. With any fixed point there is no rigid
  /// alignment, which would move them too.
  std::vector<char> FixedPoints;
  /// Added to a tissue's voxel volume for its target (mm^3, by tissue code): a piece's tets
  /// cover a little more or less than its voxels near the cuts.
  std::map<std::int32_t, double> VolumeOffsets;
  /// Where set, the boundary voxels this run answers for (targets and guards): a piece answers
  /// for its own slab, not for the false boundary where its image ends.
  BoundaryWindow VoxelWindow;
};

struct DeformationResult
{
  int Iterations = 0;                      // iterations that moved the mesh
  std::size_t Sources = 0;                 // surface and interface vertices
  std::size_t Targets = 0;                 // boundary voxels after the pattern
  std::vector<double> MeanStep;            // per iteration: mean move of the sources (mm)
  std::vector<std::size_t> HeldVertices;   // per iteration: vertices held back for quality
  std::vector<Eigen::Vector3d> Displacement; // per point, in total (mm)
  std::string StopReason;
};

/// Moves the surfaces and interfaces of a labelled tet mesh onto the image boundaries (paper,
/// section 3.3): each iteration matches every surface or interface vertex (label-set: the
/// labels of its tets, plus outside for the outer surface) to the nearest boundary voxel whose
/// label-set holds its own, within twice the local element size; a vertex farther than half
/// its element size from the boundary voxels of one of its tissues (or nearest to a boundary
/// voxel that far from the mesh) heads for that voxel instead, as it sets the tissue's
/// Hausdorff distance. Vertices move there by at most the local element size (the mean length
/// of their edges), and the interior follows through linear elasticity with the matches as
/// penalty springs. A step that would invert a tet or push a dihedral angle past
/// MinimumDihedralAngle holds the offending vertices back, and interior vertices around them
/// are smoothed to give them room for the next step; no tissue's Hausdorff distance grows. The
/// output never holds an inverted tet. Topology and labels are unchanged.
Status DeformMesh(const LabelImage& image, const TetMesh& mesh, const DeformationParams& params,
  TetMesh& out, DeformationResult& result, const Progress& progress = nullptr);

/// DeformMesh's points alone, one per point of `mesh` (its tets and labels are not copied).
Status DeformPoints(const LabelImage& image, const TetMesh& mesh, const DeformationParams& params,
  std::vector<Eigen::Vector3d>& moved, DeformationResult& result, const Progress& progress = nullptr);
} // namespace cbc3d

#endif
