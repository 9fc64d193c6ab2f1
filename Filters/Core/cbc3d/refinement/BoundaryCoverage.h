#ifndef cbc3d_BoundaryCoverage_h
#define cbc3d_BoundaryCoverage_h

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/PointGrid.h"
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/sampling/TissueComponents.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <vector>

namespace cbc3d
{
/// Where a labelled mesh's surfaces will stay far from the image boundary, the two sides of the
/// paper's Hausdorff distance: boundary voxels far from every vertex of their tissue's surface,
/// and surface vertices that cannot reach a boundary voxel of their tissue.
///
/// The surface after deformation is predicted by moving every surface vertex to its nearest
/// boundary voxel of the tissue within `reach` (deformation moves a vertex by about one element
/// size at most). Without the prediction the lattice's own offset from the boundary would count
/// as distance, and every boundary tet would look far.
class BoundaryCoverage
{
public:
  /// A face on a tissue's surface: its points (ascending) and the tet of the tissue it bounds.
  struct Face
  {
    std::array<PointId, 3> Points;
    std::int64_t Tet;
  };

  struct Gaps
  {
    std::vector<Face> FarFaces;         // the surface face nearest to each far boundary voxel, once each
    std::vector<std::int64_t> StrandedTets; // tissue tets with a surface vertex that cannot reach the boundary
    double LargestGap = 0.0;            // the farthest boundary voxel from the predicted surface (mm)
    std::int64_t FarVoxels = 0;         // boundary voxels farther than the distance from it
    /// Over MPI ranks (SetCounted): the far voxels of the rank's slab, by tissue, in place of
    /// their faces, which the ranks find together (NearestOwnedFaces).
    std::vector<std::pair<std::int32_t, Eigen::Vector3d>> Far;

    /// Whether these gaps are narrower than `before`'s: the farthest voxel nearer, or fewer
    /// voxels far. Refinement for the distance stops at a pass that gains neither: the voxels
    /// left far are beyond what splitting near them does (the nidus's thin vessels).
    bool NarrowerThan(const Gaps& before) const
    {
      return this->LargestGap < before.LargestGap || this->FarVoxels < before.FarVoxels;
    }
  };

  /// The boundary voxels of every tissue component of at least `minimumVoxels` voxels (specks
  /// are not held to a distance).
  BoundaryCoverage(const LabelImage& image, const TissueComponents& components, int minimumVoxels,
    double reach, int numberOfThreads);

  /// The gaps wider than `distance` (mm) for a mesh: `tets` over `points` with one label per tet
  /// (tets of non-tissue labels bound the tissue surfaces, as background does).
  Gaps Find(const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets,
    const std::vector<std::int32_t>& labels, double distance) const;

  /// Over MPI ranks: the boundary voxels whose gaps LargestGap and FarVoxels count (those of
  /// the rank's slab), listed in Gaps::Far when far. Unset: all, and each marks its face.
  void SetCounted(std::function<bool(const Eigen::Vector3d&)> counted) { this->Counted = std::move(counted); }

  /// Over MPI ranks: for each of `voxels` (a tissue and a boundary voxel's centre), the face of
  /// the tissue's surface nearest to it (by the predicted surface, as Find) among those whose
  /// tet is `owned`, and its distance; infinity where there is none.
  std::vector<std::pair<double, Face>> NearestOwnedFaces(const std::vector<Eigen::Vector3d>& points,
    const std::vector<Tet>& tets, const std::vector<std::int32_t>& labels,
    const std::vector<std::pair<std::int32_t, Eigen::Vector3d>>& voxels, const std::vector<char>& owned) const;

private:
  struct Tissue
  {
    std::vector<Eigen::Vector3d> Centres;
    std::unique_ptr<PointGrid> Grid;
  };
  /// Per held tissue, the faces between one of its tets and a tet of another label, or nothing.
  std::map<std::int32_t, std::vector<Face>> HeldSurfaces(std::size_t pointCount, const std::vector<Tet>& tets,
    const std::vector<std::int32_t>& labels) const;
  /// Where deformation would take a tissue's surface: each face's vertices (`stranded` where one
  /// cannot reach the boundary) and centroid, as the vertices would move.
  struct Predicted
  {
    std::vector<Eigen::Vector3d> Vertices;
    std::vector<Eigen::Vector3d> Centroids; // per face
    std::vector<char> Stranded;             // per face
  };
  Predicted Predict(const Tissue& tissue, const std::vector<Face>& faces, const std::vector<Eigen::Vector3d>& points) const;
  /// Adds one tissue's gaps, given its surface `faces` (not empty) and boundary voxels.
  void FindTissueGaps(std::int32_t label, const Tissue& tissue, const std::vector<Face>& faces,
    const std::vector<Eigen::Vector3d>& points, double distance, Gaps& gaps) const;
  std::map<std::int32_t, Tissue> Tissues;
  double Reach;
  int Threads;
  std::function<bool(const Eigen::Vector3d&)> Counted;
};
} // namespace cbc3d

#endif
