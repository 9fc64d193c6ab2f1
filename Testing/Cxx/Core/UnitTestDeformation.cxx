#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/TetGeometry.h"
#include "cbc3d/deformation/Deformation.h"
#include "cbc3d/lattice/BCCLattice.h"
#include "cbc3d/refinement/Refinement.h"
#include "cbc3d/sampling/SurfacePoints.h"

#include "TestImages.h"
#include "TestMeshes.h"
#include "TestProgress.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

namespace
{
cbc3d::LabelImage Ball()
{
  return BallImage(30, 9.0);
}

// Largest and mean distance between the ball's surface vertices and boundary voxel centres,
// both ways, by brute force.
std::pair<double, double> Distances(const cbc3d::LabelImage& image, const cbc3d::TetMesh& mesh)
{
  const auto vertices = cbc3d::TissueSurfaceVertices(mesh).at(1);
  const auto voxels = cbc3d::TissueBoundaryVoxelCentres(image).at(1);
  double largest = 0.0, sum = 0.0;
  for (const auto v : vertices)
  {
    double nearest = 1e300;
    for (const auto& b : voxels)
      nearest = std::min(nearest, (mesh.Points[v] - b).norm());
    largest = std::max(largest, nearest);
    sum += nearest;
  }
  for (const auto& b : voxels)
  {
    double nearest = 1e300;
    for (const auto v : vertices)
      nearest = std::min(nearest, (mesh.Points[v] - b).norm());
    largest = std::max(largest, nearest);
    sum += nearest;
  }
  return { largest, sum / double(vertices.size() + voxels.size()) };
}

} // namespace

TEST(Deformation, StopsAtEveryPollAssemblyIncluded)
{
  const cbc3d::LabelImage image = Ball();
  const cbc3d::TetMesh start = Lattice(image, 5.0);
  cbc3d::DeformationParams params;
  params.Iterations = 2;
  params.NumberOfThreads = 1;
  const std::vector<double> fractions = ExpectStopAtEveryPoll([&](const cbc3d::Progress& progress) {
    cbc3d::TetMesh moved;
    cbc3d::DeformationResult result;
    return cbc3d::DeformMesh(image, start, params, moved, result, progress);
  });
  // The stiffness assembly reports within (0.07, 0.1).
  EXPECT_TRUE(std::any_of(fractions.begin(), fractions.end(), [](double f) { return f > 0.07 && f < 0.1; }));
}

TEST(Deformation, BringsTheSurfaceCloserWithoutSpoilingTets)
{
  const cbc3d::LabelImage image = Ball();
  const cbc3d::TetMesh start = Lattice(image, 4.0);
  cbc3d::DeformationParams params;
  cbc3d::TetMesh moved;
  cbc3d::DeformationResult result;
  ASSERT_TRUE(cbc3d::DeformMesh(image, start, params, moved, result).IsOk());
  EXPECT_GT(result.Iterations, 0);
  EXPECT_GT(result.Sources, 0u);
  EXPECT_GT(result.Targets, 0u);
  EXPECT_EQ(moved.Tets, start.Tets);
  EXPECT_EQ(moved.Labels, start.Labels);
  EXPECT_TRUE(cbc3d::ValidateTetMesh(moved).IsOk());
  for (const auto& tet : moved.Tets)
    for (const double a : cbc3d::DihedralAngles(moved.Points[tet[0]], moved.Points[tet[1]], moved.Points[tet[2]], moved.Points[tet[3]]))
    {
      ASSERT_GE(a * cbc3d::RadiansToDegrees, params.MinimumDihedralAngle - 1e-9);
      ASSERT_LE(a * cbc3d::RadiansToDegrees, 180.0 - params.MinimumDihedralAngle + 1e-9);
    }
  const auto before = Distances(image, start);
  const auto after = Distances(image, moved);
  EXPECT_LE(after.first, before.first + 1e-12);   // the Hausdorff distance never grows
  EXPECT_LT(after.second, 0.8 * before.second);   // and the surface comes closer on the whole
  for (std::size_t p = 0; p < moved.Points.size(); ++p)
    EXPECT_TRUE((moved.Points[p] - start.Points[p]).isApprox(result.Displacement[p], 1e-9) ||
      result.Displacement[p].norm() < 1e-12);
}

TEST(Deformation, SameResultForOneAndTwoThreadsAndZeroIterationsChangesNothing)
{
  const cbc3d::LabelImage image = Ball();
  const cbc3d::TetMesh start = Lattice(image, 5.0);
  cbc3d::DeformationParams params;
  params.Iterations = 3;
  cbc3d::TetMesh one, two;
  cbc3d::DeformationResult r1, r2;
  params.NumberOfThreads = 1;
  ASSERT_TRUE(cbc3d::DeformMesh(image, start, params, one, r1).IsOk());
  params.NumberOfThreads = 2;
  ASSERT_TRUE(cbc3d::DeformMesh(image, start, params, two, r2).IsOk());
  EXPECT_EQ(one.Points, two.Points);
  params.Iterations = 0;
  ASSERT_TRUE(cbc3d::DeformMesh(image, start, params, one, r1).IsOk());
  EXPECT_EQ(one.Points, start.Points);
  params.Iterations = 2;
  params.Penalty = -1;
  EXPECT_FALSE(cbc3d::DeformMesh(image, start, params, one, r1).IsOk());
}

namespace
{
// A ball of radius 11 mm (voxel centres within 11 mm of the image centre, 1 mm voxels) meshed
// coarsely (8 mm lattice), refined and deformed with the defaults.
cbc3d::TetMesh DeformedBall(const cbc3d::LabelImage& image, const cbc3d::DeformationParams& params = {})
{
  cbc3d::TetMesh refined, deformed;
  cbc3d::RefinementResult refinedResult;
  EXPECT_TRUE(cbc3d::RefineMesh(image, Lattice(image, 8.0), cbc3d::RefinementParams(), refined, refinedResult).IsOk());
  cbc3d::DeformationResult result;
  EXPECT_TRUE(cbc3d::DeformMesh(image, refined, params, deformed, result).IsOk());
  return deformed;
}

// Volume-weighted centroid and volume.
std::pair<Eigen::Vector3d, double> CentroidAndVolume(const cbc3d::TetMesh& mesh)
{
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double volume = 0.0;
  for (const auto& t : mesh.Tets)
  {
    const auto& p = mesh.Points;
    const double v = cbc3d::SignedVolume(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
    sum += v * (p[t[0]] + p[t[1]] + p[t[2]] + p[t[3]]) / 4.0;
    volume += v;
  }
  return { sum / volume, volume };
}
} // namespace

TEST(Deformation, CoarseBallEndsOnItsSphere)
{
  // Ball of radius 11 voxels. Its boundary voxel centres (the registration targets, and the
  // points the paper's Hausdorff distance measures to) lie within one voxel inside the sphere:
  // a centre at 10 or less has all its face-neighbours inside.
  const cbc3d::LabelImage image = BallImage(32, 11.0);
  const Eigen::Vector3d centre = Eigen::Vector3d::Constant(15.5);
  const auto voxelsByTissue = cbc3d::TissueBoundaryVoxelCentres(image);
  const auto& voxels = voxelsByTissue.at(1);
  auto offSphere = [&](const Eigen::Vector3d& x) { return (x - centre).norm() - 11.0; };
  auto toVoxels = [&](const Eigen::Vector3d& x) {
    double nearest = 1e9;
    for (const auto& v : voxels)
      nearest = std::min(nearest, (x - v).norm());
    return nearest;
  };
  for (const auto& v : voxels)
    ASSERT_TRUE(offSphere(v) < 0.0 && offSphere(v) >= -1.0);

  // Every surface vertex ends within one voxel of the image's boundary voxels (measured: 0.87,
  // just over half a voxel diagonal, 0.866); the surface as a whole lies on them (its mean
  // depth under the sphere within a quarter voxel of theirs); and no vertex ends more than half
  // a voxel outside the sphere, or deeper inside than the deepest voxel centre (one voxel)
  // plus half a voxel.
  cbc3d::DeformationParams atCentres; // the paper's targets (the default is on faces)
  atCentres.Placement = cbc3d::TargetPlacement::VoxelCentre;
  atCentres.KeepVolumes = false;      // where the targets alone put the surface
  const cbc3d::TetMesh mesh = DeformedBall(image, atCentres);
  const auto surfaceByTissue = cbc3d::TissueSurfaceVertices(mesh);
  const auto& surface = surfaceByTissue.at(1);
  double farthestFromVoxels = 0.0, deepest = 0.0, outermost = -1e9, vertexDepth = 0.0, voxelDepth = 0.0;
  for (const auto v : surface)
  {
    farthestFromVoxels = std::max(farthestFromVoxels, toVoxels(mesh.Points[v]));
    deepest = std::min(deepest, offSphere(mesh.Points[v]));
    outermost = std::max(outermost, offSphere(mesh.Points[v]));
    vertexDepth += offSphere(mesh.Points[v]) / double(surface.size());
  }
  for (const auto& v : voxels)
    voxelDepth += offSphere(v) / double(voxels.size());
  EXPECT_LE(farthestFromVoxels, 1.0);
  EXPECT_NEAR(vertexDepth, voxelDepth, 0.25);
  EXPECT_GE(deepest, -1.5);
  EXPECT_LE(outermost, 0.5);

  // Before deformation the lattice's surface is far off.
  const auto lattice = Lattice(image, 8.0);
  const auto latticeByTissue = cbc3d::TissueSurfaceVertices(lattice);
  double latticeFarthest = 0.0;
  for (const auto v : latticeByTissue.at(1))
    latticeFarthest = std::max(latticeFarthest, std::abs(offSphere(lattice.Points[v])));
  EXPECT_GT(latticeFarthest, 2.0);
}

TEST(Deformation, RigidlyShiftedImageMovesTheMeshRigidly)
{
  // A mesh fitted to a ball, deformed onto the same ball moved 2 voxels along x: the mesh
  // moves as a whole (its centroid and its vertices by the shift, its volume kept) and no tet
  // is spoilt.
  const cbc3d::LabelImage image = BallImage(32, 11.0);
  cbc3d::DeformationParams params;
  params.Placement = cbc3d::TargetPlacement::VoxelCentre; // the same targets before and after
  params.KeepVolumes = false; // the targets alone: a rigid shift of them is all that changes
  const cbc3d::TetMesh fitted = DeformedBall(image, params);
  cbc3d::LabelImage shifted = Cube(32, 0);
  for (int k = 0; k < 32; ++k)
    for (int j = 0; j < 32; ++j)
      for (int i = 2; i < 32; ++i)
        shifted.Labels[shifted.VoxelIndex(i, j, k)] = image.LabelAt(i - 2, j, k);
  cbc3d::TetMesh moved;
  cbc3d::DeformationResult result;
  ASSERT_TRUE(cbc3d::DeformMesh(shifted, fitted, params, moved, result).IsOk());
  const auto before = CentroidAndVolume(fitted), after = CentroidAndVolume(moved);
  EXPECT_NEAR((after.first - before.first).x(), 2.0, 0.1);
  EXPECT_NEAR((after.first - before.first).y(), 0.0, 0.1);
  EXPECT_NEAR((after.first - before.first).z(), 0.0, 0.1);
  EXPECT_NEAR(after.second / before.second, 1.0, 0.02);
  // Vertex by vertex: the bulk moves by the shift (median deviation under 0.05 voxel), and
  // none strays from it by much more than a voxel (the elastic step still fits the surface; the
  // worst one vertex: 1.02 voxels, 1.20 since refinement's background ring changed the ball's
  // mesh by 10 tets, with 99% under 0.6).
  std::vector<double> deviation;
  for (std::size_t p = 0; p < moved.Points.size(); ++p)
    deviation.push_back((moved.Points[p] - fitted.Points[p] - Eigen::Vector3d(2.0, 0.0, 0.0)).norm());
  std::sort(deviation.begin(), deviation.end());
  EXPECT_LT(deviation[deviation.size() / 2], 0.05);
  EXPECT_LE(deviation.back(), 1.25);
  EXPECT_LT(deviation[deviation.size() * 99 / 100], 0.65);
  for (const auto& tet : moved.Tets)
    ASSERT_TRUE(cbc3d::DihedralAnglesWithin(moved.Points[tet[0]], moved.Points[tet[1]], moved.Points[tet[2]],
      moved.Points[tet[3]], params.MinimumDihedralAngle / cbc3d::RadiansToDegrees * (1.0 - 1e-9)));

  // Without the rigid part the elastic step alone, held back by the quality guard, lags.
  params.RigidAlignment = false;
  ASSERT_TRUE(cbc3d::DeformMesh(shifted, fitted, params, moved, result).IsOk());
  EXPECT_LT((CentroidAndVolume(moved).first - before.first).x(), 1.0);
}

TEST(Deformation, FaceTargetsKeepTheBallsVolume)
{
  // The paper's targets, boundary voxel centres, sit about 0.4 voxel inside the sphere on
  // average, so the mesh comes out smaller than the voxels. With targets on the label boundary
  // its surface vertices lie on the sphere on average (within 0.15 voxel), and it keeps the
  // voxels' volume within 4.5%.
  const cbc3d::LabelImage image = BallImage(32, 11.0);
  double voxels = 0.0;
  for (const auto label : image.Labels)
    voxels += label == 1 ? 1.0 : 0.0;
  const Eigen::Vector3d centre = Eigen::Vector3d::Constant(15.5);
  auto volumeAndDepth = [&](const cbc3d::TetMesh& mesh) {
    const auto surfaceByTissue = cbc3d::TissueSurfaceVertices(mesh);
    double depth = 0.0;
    for (const auto v : surfaceByTissue.at(1))
      depth += ((mesh.Points[v] - centre).norm() - 11.0) / double(surfaceByTissue.at(1).size());
    return std::make_pair(CentroidAndVolume(mesh).second, depth);
  };
  cbc3d::DeformationParams params;
  params.KeepVolumes = false; // where each placement of the targets alone puts the surface
  params.Placement = cbc3d::TargetPlacement::VoxelCentre;
  const auto atCentres = volumeAndDepth(DeformedBall(image, params));
  params.Placement = cbc3d::TargetPlacement::VoxelFace;
  const auto atFaces = volumeAndDepth(DeformedBall(image, params));
  EXPECT_EQ(cbc3d::DeformationParams().Placement, cbc3d::TargetPlacement::VoxelFace); // the default
  EXPECT_LT(atCentres.first / voxels, atFaces.first / voxels);
  EXPECT_LT(std::abs(atFaces.second), std::abs(atCentres.second));
  EXPECT_NEAR(atFaces.second, 0.0, 0.15);
  // The chords' share of a ball this size, and the vertices steered towards voxel centres for
  // the Hausdorff distance, which sit half a voxel inside.
  EXPECT_NEAR(atFaces.first / voxels, 1.0, 0.045);
}

TEST(Deformation, KeepVolumesHoldsTheVoxelsVolumeWithoutLosingFidelity)
{
  // A ball of radius 6 voxels on a lattice of 8: its faces are chords of a strongly curved
  // boundary, so the targets alone leave it short of its voxels' volume. Keeping volumes brings
  // it within 0.5%, with no tissue's Hausdorff distance larger and every angle within the bound.
  const cbc3d::LabelImage image = BallImage(24, 6.0);
  double voxels = 0.0;
  for (const auto label : image.Labels)
    voxels += label == 1 ? 1.0 : 0.0;
  cbc3d::DeformationParams params;
  params.KeepVolumes = false;
  const cbc3d::TetMesh free = DeformedBall(image, params);
  params.KeepVolumes = true;
  EXPECT_TRUE(cbc3d::DeformationParams().KeepVolumes); // the default
  const cbc3d::TetMesh kept = DeformedBall(image, params);
  const double freeShare = CentroidAndVolume(free).second / voxels;
  const double keptShare = CentroidAndVolume(kept).second / voxels;
  std::printf("ball volume / voxels: %.4f free, %.4f kept\n", freeShare, keptShare);
  EXPECT_LT(freeShare, 0.99);
  EXPECT_NEAR(keptShare, 1.0, 0.005);
  EXPECT_LE(Distances(image, kept).first, Distances(image, free).first + 1e-9);
  for (const auto& tet : kept.Tets)
    ASSERT_TRUE(cbc3d::DihedralAnglesWithin(kept.Points[tet[0]], kept.Points[tet[1]], kept.Points[tet[2]],
      kept.Points[tet[3]], params.MinimumDihedralAngle / cbc3d::RadiansToDegrees * (1.0 - 1e-9)));
}

// A piece of a larger mesh: its fixed points keep their places to the bit while the rest move
// within the angle bound, and a volume offset moves a tissue's target by that much.
TEST(Deformation, FixedPointsKeepTheirPlacesAndVolumeOffsetsMoveTheTarget)
{
  const cbc3d::LabelImage image = BallImage(24, 6.0);
  cbc3d::TetMesh refined, moved;
  cbc3d::RefinementResult refinedResult;
  ASSERT_TRUE(cbc3d::RefineMesh(image, Lattice(image, 8.0), cbc3d::RefinementParams(), refined, refinedResult).IsOk());
  std::vector<double> xs;
  for (const auto& p : refined.Points)
    xs.push_back(p.x());
  std::nth_element(xs.begin(), xs.begin() + xs.size() / 2, xs.end());
  cbc3d::DeformationParams params;
  for (const auto& p : refined.Points)
    params.FixedPoints.push_back(p.x() < xs[xs.size() / 2] ? 1 : 0);
  cbc3d::DeformationResult result;
  ASSERT_TRUE(cbc3d::DeformMesh(image, refined, params, moved, result).IsOk());
  std::size_t freeMoved = 0;
  for (std::size_t p = 0; p < refined.Points.size(); ++p)
  {
    if (params.FixedPoints[p])
      ASSERT_EQ(moved.Points[p], refined.Points[p]) << "fixed point " << p;
    else
      freeMoved += (moved.Points[p] - refined.Points[p]).norm() > 1e-3;
  }
  EXPECT_GT(freeMoved, 10u);
  for (const auto& tet : moved.Tets)
    ASSERT_TRUE(cbc3d::DihedralAnglesWithin(moved.Points[tet[0]], moved.Points[tet[1]], moved.Points[tet[2]],
      moved.Points[tet[3]], params.MinimumDihedralAngle / cbc3d::RadiansToDegrees * (1.0 - 1e-9)));
  // One flag per point, or none.
  params.FixedPoints.pop_back();
  EXPECT_FALSE(cbc3d::DeformMesh(image, refined, params, moved, result).IsOk());

  double voxels = 0.0;
  for (const auto label : image.Labels)
    voxels += label == 1 ? image.Spacing.prod() : 0.0;
  cbc3d::DeformationParams offset;
  offset.VolumeOffsets[1] = -0.02 * voxels;
  const double share = CentroidAndVolume(DeformedBall(image, offset)).second / voxels;
  std::printf("ball volume / voxels with a -2%% offset: %.4f\n", share);
  EXPECT_NEAR(share, 0.98, 0.005);
}
