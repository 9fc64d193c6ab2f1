// The boundary-distance criterion of refinement: on a ball meshed with a coarse lattice, every
// boundary voxel ends near a vertex of the deformed surface when it is on, and not when it is off.
#include "cbc3d/deformation/Deformation.h"
#include "cbc3d/lattice/BCCLattice.h"
#include "cbc3d/refinement/BoundaryCoverage.h"
#include "cbc3d/refinement/Refinement.h"
#include "cbc3d/sampling/SurfacePoints.h"
#include "cbc3d/sampling/TissueComponents.h"

#include "TestImages.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{

// Lattice, refinement with the given bound, deformation; returns the farthest boundary voxel
// from the surface vertices (brute force), and the tet count.
std::pair<double, std::size_t> FarthestBoundaryVoxel(const cbc3d::LabelImage& image, double bound)
{
  const cbc3d::TetMesh lattice = Lattice(image, 8.0);
  cbc3d::TetMesh refined, deformed;
  cbc3d::RefinementParams refinement;
  refinement.Fidelity = 0.5; // met at the lattice: only the boundary distance refines
  refinement.BoundaryDistance = bound;
  cbc3d::RefinementResult refinedResult;
  EXPECT_TRUE(cbc3d::RefineMesh(image, lattice, refinement, refined, refinedResult).IsOk());
  cbc3d::DeformationResult deformedResult;
  EXPECT_TRUE(cbc3d::DeformMesh(image, refined, cbc3d::DeformationParams(), deformed, deformedResult).IsOk());
  const auto vertices = cbc3d::TissueSurfaceVertices(deformed).at(1);
  double farthest = 0.0;
  const auto boundary = cbc3d::TissueBoundaryVoxelCentres(image);
  for (const auto& voxel : boundary.at(1))
  {
    double nearest = 1e300;
    for (const auto v : vertices)
      nearest = std::min(nearest, (deformed.Points[v] - voxel).norm());
    farthest = std::max(farthest, nearest);
  }
  return { farthest, deformed.Tets.size() };
}
} // namespace

TEST(BoundaryCoverage, BoundsTheDistanceFromBoundaryVoxelsToTheDeformedSurface)
{
  // The surface is predicted, not deformed, during refinement: allow half a voxel diagonal.
  const cbc3d::LabelImage image = BallImage(32, 11.0); // radius 11 mm in 1 mm voxels
  const double bound = 3.0, slack = 0.5 * std::sqrt(3.0);
  const auto on = FarthestBoundaryVoxel(image, 0.0); // automatic: 3/8 of the 8 mm lattice
  EXPECT_LE(on.first, bound + slack);
  const auto off = FarthestBoundaryVoxel(image, -1.0);
  EXPECT_GT(off.first, bound + slack); // the lattice's faces alone leave voxels farther
  EXPECT_GT(on.second, off.second);
}

TEST(BoundaryCoverage, GapsNarrowWhenTheFarthestComesNearerOrFewerStayFar)
{
  cbc3d::BoundaryCoverage::Gaps before, after;
  before.LargestGap = 5.15;
  before.FarVoxels = 4;
  after = before;
  EXPECT_FALSE(after.NarrowerThan(before)); // the nidus's passes 5 to 7: nothing gained
  after.FarVoxels = 5;
  EXPECT_FALSE(after.NarrowerThan(before));
  after.LargestGap = 5.14;
  EXPECT_TRUE(after.NarrowerThan(before)); // the farthest came nearer, though one more is far
  after = before;
  after.FarVoxels = 3;
  EXPECT_TRUE(after.NarrowerThan(before)); // the brain at defaults: the farthest stayed at
  after.LargestGap = 6.0;                  // 2.72 mm for three passes while 33, 6, 1 stayed far
  EXPECT_TRUE(after.NarrowerThan(before));
}
