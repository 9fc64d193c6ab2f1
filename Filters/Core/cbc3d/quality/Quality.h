#ifndef cbc3d_Quality_h
#define cbc3d_Quality_h

// Stage: quality and topology. Takes a labelled mesh and its label image; gives dihedral angles,
// Hausdorff distances (SurfaceDistance.h) and volumes per tissue (this file), and components,
// hinges and Euler characteristics against the image's (MeshTopology.h, ImageTopology.h).

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/TetMesh.h"

#include <cstdint>
#include <limits>
#include <map>
#include <vector>

namespace cbc3d
{
/// The thresholds users compare meshers by: slivers and needles show up as either.
constexpr double SmallAngleDegrees = 10.0;
constexpr double LargeAngleDegrees = 170.0;

/// Dihedral-angle figures of a set of tets, in degrees.
struct DihedralSummary
{
  std::int64_t Tets = 0;
  double MinDegrees = std::numeric_limits<double>::infinity();
  double MaxDegrees = -std::numeric_limits<double>::infinity();
  std::int64_t Inverted = 0;   // tets with non-positive volume
  std::int64_t SmallAngle = 0; // tets with a dihedral angle under SmallAngleDegrees
  std::int64_t LargeAngle = 0; // tets with a dihedral angle over LargeAngleDegrees

  void Merge(const DihedralSummary& other);
};

struct QualitySummary
{
  DihedralSummary Overall;
  std::map<std::int32_t, DihedralSummary> Tissues; // keyed by label value
};

/// Per-tet extremes, in degrees, indexed like mesh.Tets.
struct TetDihedralExtremes
{
  std::vector<double> MinDegrees;
  std::vector<double> MaxDegrees;
};

/// Minimum and maximum dihedral angle and inverted-tet count, overall and per tissue; fills
/// `perTet` when given. Deterministic for any thread count (min/max/count are exact).
QualitySummary SummarizeQuality(const TetMesh& mesh, int numberOfThreads = 0,
  TetDihedralExtremes* perTet = nullptr);
/// Each tissue's volume in the mesh (sum of its tets' signed volumes, mm^3), summed in tet
/// order so that it is the same on every run.
std::map<std::int32_t, double> TissueMeshVolumes(const TetMesh& mesh);

/// Each tissue's volume in the image: its voxel count times the voxel volume (mm^3). Counted on
/// `numberOfThreads` threads (0 = all cores); whole numbers, so the same for any count.
std::map<std::int32_t, double> TissueImageVolumes(const LabelImage& image, int numberOfThreads = 0);
} // namespace cbc3d

#endif
