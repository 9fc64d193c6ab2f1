#ifndef cbc3d_TissueVolumes_h
#define cbc3d_TissueVolumes_h

#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/TetMesh.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace cbc3d
{
/// Keeps each tissue's volume at its voxels' while deformation moves the surfaces.
///
/// Why: a surface whose vertices lie on the image boundary is a polyhedron inscribed in it, so
/// a thin or curved tissue loses the volume between its faces and the boundary (the
/// ventricles: 92% of their voxels' volume with every vertex on target). Labelling a thin sheet
/// by whole tets loses more. Here each interface between two tissues (or a tissue and the
/// outside) is offset along its normals by one distance, chosen so that every tissue's volume
/// meets its target to first order, with the least area-weighted sum of squared offsets.
/// The topology of the mesh is fixed, so the interface faces are found once.
class TissueVolumeKeeper
{
public:
  /// `targets`: the volume each tissue label should have (mm^3); tissues without one are free.
  /// `largestOffset`: no interface moves farther than this in one call (mm).
  TissueVolumeKeeper(const TetMesh& mesh, std::map<std::int32_t, double> targets, double largestOffset);
  /// The same from the mesh's faces (FindMeshFaces, or SurfaceFaces: faces inside a tissue are
/// ignored), when the caller has them already.
  TissueVolumeKeeper(const TetMesh& mesh, const std::vector<MeshFace>& faces, std::map<std::int32_t, double> targets,
    double largestOffset);

  /// Each tissue's volume with the points at `x`, from its boundary faces (divergence theorem).
  std::map<std::int32_t, double> Volumes(const std::vector<Eigen::Vector3d>& x) const;

  /// The largest relative difference between a tissue's volume at `x` and its target.
  double LargestRelativeShortfall(const std::vector<Eigen::Vector3d>& x) const;
  /// The same from the tissues' volumes (Volumes).
  double LargestRelativeShortfall(const std::map<std::int32_t, double>& volumes) const;

  /// The volume each tissue should have (mm^3).
  const std::map<std::int32_t, double>& TargetVolumes() const { return this->Targets; }

  /// Area vectors (half the cross product, out of the pair's first tissue) of each pair's faces
  /// summed at each moving point: (point, pair, sum), sorted by point.
  struct PointPairArea
  {
    PointId Point;
    int Pair;
    Eigen::Vector3d Area;
  };

  /// Which faces' areas sum at which (moving point, pair), and in what order: fixed while the
  /// moving points are, so the rounds of a restoration find it once, not a sort each round.
  class AreaSums
  {
  public:
    AreaSums(const TissueVolumeKeeper& keeper, const std::vector<char>& moving);
    /// The sums at `x`, on `threads`: each (point, pair) adds its faces in the plan's order, so
    /// the same bits for any number of threads.
    std::vector<PointPairArea> At(const std::vector<Eigen::Vector3d>& x, int threads) const;

  private:
    const TissueVolumeKeeper& Keeper;
    std::vector<PointPairArea> Sums; // point and pair of each sum (areas filled by At)
    std::vector<std::int64_t> Start; // sum i adds the faces FaceOf[Start[i]] .. FaceOf[Start[i + 1] - 1]
    std::vector<std::int32_t> FaceOf;
  };

  /// Moves the goals of the moving points (goal per point, `moving` per point) so that, with
  /// every moving point at its goal and the rest in place, each tissue meets its target to
  /// first order; a tissue in `aims` aims at that volume instead. Returns the largest
  /// interface offset applied (mm).
  double OffsetGoals(std::vector<Eigen::Vector3d>& goals, const std::vector<char>& moving,
    const std::map<std::int32_t, double>& aims = {}) const;
  /// The same with the sums planned for the moving points and the tissues' volumes at `goals`
  /// (Volumes(goals)), on `threads`.
  double OffsetGoals(std::vector<Eigen::Vector3d>& goals, const AreaSums& sums,
    const std::map<std::int32_t, double>& volumes, const std::map<std::int32_t, double>& aims, int threads) const;

private:
  struct InterfaceFace
  {
    std::array<PointId, 3> Points; // ordered so the normal points out of Pairs[Pair].first
    int Pair;
  };
  Eigen::VectorXd InterfaceOffsets(const std::vector<PointPairArea>& areas,
    const std::map<std::int32_t, double>& volumes, const std::map<std::int32_t, double>& aims) const;

  std::vector<std::pair<std::int32_t, std::int32_t>> Pairs; // (tissue, other tissue or Outside)
  std::vector<InterfaceFace> Faces;
  std::map<std::int32_t, double> Targets;
  double LargestOffset;
};
} // namespace cbc3d

#endif
