#ifndef cbc3d_FidelityGuard_h
#define cbc3d_FidelityGuard_h

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/PointGrid.h"
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/sampling/SurfacePoints.h"

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace cbc3d
{
/// Keeps each tissue's Hausdorff distance from growing: the distance between the tissue's
/// surface vertices and its boundary voxel centres (the measure vtkCBC3DMeshQuality reports).
/// It keeps each tissue's vertices at the last accepted positions, with a grid over them.
class FidelityGuard
{
public:
  /// Measures every tissue's distance, asking `keepGoing` before each; when it says stop, the
  /// guard is left unfinished.
  /// `faces` are the mesh's (FindMeshFaces, or SurfaceFaces: faces inside a tissue are ignored).
  /// `boundary` are the image's TissueBoundaryVoxels; `cell` the cell size of the grids over them.
  /// With `fixed` (one flag per point; empty: none), the distance counts only the vertices that
  /// may move and the voxels nearest to them: a piece of a larger mesh answers for its own
  /// part, not for the vertices held at its edges, whose nearest voxels may lie beyond its image.
  FidelityGuard(const LabelImage& image, const TissueVoxels& boundary, const TetMesh& mesh,
    const std::vector<MeshFace>& faces, double cell, int threads, const std::function<bool()>& keepGoing,
    const std::vector<char>& fixed = {});

  /// Holds back (share 0) the vertices whose step from the accepted positions to `trial` would
  /// push a tissue's Hausdorff distance past its current value: vertices that would end farther
  /// from the tissue's boundary voxels, and the former nearest vertices of boundary voxels that
  /// would be left farther from the mesh. Returns how many vertices it held. Asks `keepGoing`
  /// before each tissue; when it says stop, returns at once (the count then means nothing).
  std::size_t Hold(const std::vector<Eigen::Vector3d>& trial, std::vector<double>& share,
    const std::function<bool()>& keepGoing) const;

  /// Takes these positions, and their distances as the new limits, unless some tissue's would
  /// grow; returns whether it took them. Asks `keepGoing` before each tissue (false when
  /// stopped).
  bool AcceptIfNoneGrows(const std::vector<Eigen::Vector3d>& points, const std::function<bool()>& keepGoing);

  /// Takes these positions, and their distances as the new limits where smaller. Asks
  /// `keepGoing` before each tissue; when it says stop, returns at once.
  void Accept(const std::vector<Eigen::Vector3d>& points, const std::function<bool()>& keepGoing);

  /// Goals for the vertices that set a tissue's Hausdorff distance, at the accepted positions:
  /// of the boundary voxels whose nearest vertex of the tissue a point is, and the point's
  /// nearest boundary voxel of each of its tissues (when within `search[point]`), the farthest,
  /// if farther than `reach[point]`; the goal is that voxel's centre, with either target
  /// placement: these vertices set the Hausdorff distance, which measures to centres, so with
  /// face targets the bulk of the surface keeps the tissue's volume while its worst points do
  /// not drift half a voxel off that measure (brain, paper's settings, face: 3.58 -> 3.41 mm).
  /// `steered[point]` is 0 where there is none.
  void Steer(const std::vector<double>& reach, const std::vector<double>& search,
    std::vector<Eigen::Vector3d>& goal, std::vector<char>& steered) const;

private:
  // A tissue's surface vertices at some positions, with a grid over them (the grid refers to
  // the positions, so a snapshot stays where it was made: it is neither copied nor moved).
  struct Snapshot
  {
    Snapshot(const std::vector<PointId>& ids, const std::vector<Eigen::Vector3d>& points, double cell)
    {
      this->Points.reserve(ids.size());
      for (const PointId v : ids)
      {
        this->Points.push_back(points[v]);
      }
      this->Grid = std::make_unique<PointGrid>(this->Points, cell);
    }
    Snapshot(const Snapshot&) = delete;
    Snapshot& operator=(const Snapshot&) = delete;

    std::vector<Eigen::Vector3d> Points;
    std::unique_ptr<PointGrid> Grid;
    std::vector<int> NearestVertex; // per boundary voxel of the tissue, once measured
    std::vector<int> NearestVoxel;  // per vertex, once measured
  };

  struct Tissue
  {
    std::int32_t Label;
    std::vector<PointId> Vertices;
    std::vector<char> Counted;           // per vertex: whether the distance counts it (empty: all)
    std::vector<Eigen::Vector3d> Voxels; // boundary voxel centres, which the distance measures to
    double Hausdorff = 0.0;
    std::unique_ptr<PointGrid> Grid;        // over Voxels
    std::unique_ptr<Snapshot> Current;      // the vertices at the accepted positions
  };

  // Two-sided distance between the tissue's boundary voxels and its vertices at `at`; keeps
  // each voxel's nearest vertex and each vertex's nearest voxel in `at` (Steer reads them).
  double Measure(const Tissue& tissue, Snapshot& at) const;

  double Cell;       // of the grids over boundary voxels: about a voxel
  double VertexCell; // of the grids over vertices: at least the mean surface edge
  int Threads;
  std::vector<Tissue> Tissues;
};
} // namespace cbc3d

#endif
