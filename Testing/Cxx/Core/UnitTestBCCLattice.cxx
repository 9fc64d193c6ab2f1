#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/TetGeometry.h"
#include "cbc3d/base/TetTopology.h"
#include "cbc3d/lattice/BCCLattice.h"

#include "TestImages.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace
{
// A ball of `label` in an n^3 image, decided in world space.
cbc3d::LabelImage Ball(int n, double radius, std::int32_t label, const Eigen::Vector3d& spacing,
  const Eigen::Matrix3d& direction, const Eigen::Vector3d& origin)
{
  cbc3d::LabelImage image = Cube(n, 0);
  image.Spacing = spacing;
  image.Direction = direction;
  image.Origin = origin;
  PaintBall(image, image.IndexToWorld(Eigen::Vector3d::Constant((n - 1) / 2.0)), radius, label);
  return image;
}

// Marks the voxels whose centres lie in some tet (barycentric test written here, apart from
// the sampler the lattice uses).
std::vector<bool> CoveredVoxels(const cbc3d::LabelImage& image, const cbc3d::TetMesh& mesh)
{
  std::vector<bool> covered(image.Labels.size(), false);
  for (const cbc3d::Tet& tet : mesh.Tets)
  {
    Eigen::Matrix<double, 3, 4> index;
    for (int v = 0; v < 4; ++v)
      index.col(v) = image.WorldToIndex(mesh.Points[tet[v]]);
    Eigen::Matrix3d edges;
    edges << index.col(1) - index.col(0), index.col(2) - index.col(0), index.col(3) - index.col(0);
    const Eigen::Matrix3d inverse = edges.inverse();
    const Eigen::Vector3d lo = index.rowwise().minCoeff(), hi = index.rowwise().maxCoeff();
    for (int k = std::max(0, int(std::ceil(lo[2]))); k <= std::min(image.Dimensions[2] - 1, int(std::floor(hi[2]))); ++k)
      for (int j = std::max(0, int(std::ceil(lo[1]))); j <= std::min(image.Dimensions[1] - 1, int(std::floor(hi[1]))); ++j)
        for (int i = std::max(0, int(std::ceil(lo[0]))); i <= std::min(image.Dimensions[0] - 1, int(std::floor(hi[0]))); ++i)
        {
          const Eigen::Vector3d b = inverse * (Eigen::Vector3d(i, j, k) - index.col(0));
          if (b.minCoeff() >= -1e-9 && b.sum() <= 1 + 1e-9)
            covered[image.VoxelIndex(i, j, k)] = true;
        }
  }
  return covered;
}

void ExpectBCCAngles(const cbc3d::TetMesh& mesh)
{
  for (const cbc3d::Tet& tet : mesh.Tets)
  {
    const auto& p = mesh.Points;
    auto angles = cbc3d::DihedralAngles(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]);
    std::sort(angles.begin(), angles.end());
    for (int e = 0; e < 6; ++e)
    {
      ASSERT_NEAR(angles[e] * cbc3d::RadiansToDegrees, e < 4 ? 60.0 : 90.0, 1e-6);
    }
    ASSERT_GT(cbc3d::SignedVolume(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]), 0.0);
  }
}

void ExpectCovers(const cbc3d::LabelImage& image, const cbc3d::TetMesh& mesh)
{
  const std::vector<bool> covered = CoveredVoxels(image, mesh);
  std::int64_t missed = 0;
  for (std::size_t v = 0; v < covered.size(); ++v)
    missed += image.IsTissue(image.Labels[v]) && !covered[v];
  EXPECT_EQ(missed, 0);
}

// Every face is used by one tet (boundary) or two (interior), never more.
void ExpectConforming(const cbc3d::TetMesh& mesh)
{
  std::map<std::array<cbc3d::PointId, 3>, int> faces;
  for (const cbc3d::Tet& tet : mesh.Tets)
    for (const auto& f : cbc3d::TetFaces)
    {
      std::array<cbc3d::PointId, 3> key = { tet[f[0]], tet[f[1]], tet[f[2]] };
      std::sort(key.begin(), key.end());
      ++faces[key];
    }
  for (const auto& [face, uses] : faces)
    ASSERT_LE(uses, 2);
}
} // namespace

TEST(BCCLattice, BallLatticeHasBCCAnglesCoversTheTissueAndConforms)
{
  const cbc3d::LabelImage image = Ball(24, 8.0, 1, Eigen::Vector3d::Ones(), Eigen::Matrix3d::Identity(),
    Eigen::Vector3d::Zero());
  cbc3d::LatticeParams params;
  params.EdgeLength = 4.0;
  cbc3d::TetMesh mesh;
  ASSERT_TRUE(cbc3d::BuildBCCLattice(image, params, mesh).IsOk());
  ASSERT_GT(mesh.Tets.size(), 100u);
  EXPECT_TRUE(cbc3d::ValidateTetMesh(mesh).IsOk());
  ExpectBCCAngles(mesh);
  ExpectCovers(image, mesh);
  ExpectConforming(mesh);
  for (const std::int32_t label : mesh.Labels)
    EXPECT_EQ(label, 1);
  // Every BCC tet of edge h has volume h^3 / 12; together they hold at least the ball.
  const double ballVolume = 4.0 / 3.0 * M_PI * 8.0 * 8.0 * 8.0;
  EXPECT_GT(mesh.Tets.size() * 64.0 / 12.0, ballVolume);
}

TEST(BCCLattice, ReflectedAnisotropicImageGivesPositiveTetsInTheWorldFrame)
{
  Eigen::Matrix3d direction =
    Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  direction.col(1) *= -1.0; // a reflection
  const cbc3d::LabelImage image =
    Ball(20, 7.0, 128, Eigen::Vector3d(0.8, 1.0, 1.5), direction, Eigen::Vector3d(-40, 12, 100));
  cbc3d::LatticeParams params;
  params.EdgeLength = 3.0;
  cbc3d::TetMesh mesh;
  ASSERT_TRUE(cbc3d::BuildBCCLattice(image, params, mesh).IsOk());
  ExpectBCCAngles(mesh);
  ExpectCovers(image, mesh);
  ExpectConforming(mesh);
  EXPECT_EQ(std::count(mesh.Labels.begin(), mesh.Labels.end(), 128), std::ptrdiff_t(mesh.Labels.size()));
  // The mesh sits around the ball's world centre, not around the index-space origin.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : mesh.Points)
    mean += p;
  mean /= double(mesh.Points.size());
  const Eigen::Vector3d centre = image.IndexToWorld(Eigen::Vector3d::Constant(9.5));
  EXPECT_LT((mean - centre).norm(), 3.0);
}

TEST(BCCLattice, TwoTissuesKeepTheirLabels)
{
  cbc3d::LabelImage image;
  image.Dimensions = { 20, 10, 10 };
  image.Labels.assign(2000, 0);
  for (int k = 2; k < 8; ++k)
    for (int j = 2; j < 8; ++j)
      for (int i = 2; i < 18; ++i)
        image.Labels[image.VoxelIndex(i, j, k)] = i < 10 ? 5 : 9;
  cbc3d::LatticeParams params;
  params.EdgeLength = 2.0;
  cbc3d::TetMesh mesh;
  ASSERT_TRUE(cbc3d::BuildBCCLattice(image, params, mesh).IsOk());
  EXPECT_GT(std::count(mesh.Labels.begin(), mesh.Labels.end(), 5), 0);
  EXPECT_GT(std::count(mesh.Labels.begin(), mesh.Labels.end(), 9), 0);
  EXPECT_EQ(std::count(mesh.Labels.begin(), mesh.Labels.end(), 5) +
      std::count(mesh.Labels.begin(), mesh.Labels.end(), 9),
    std::ptrdiff_t(mesh.Labels.size()));
  ExpectCovers(image, mesh);
}

TEST(BCCLattice, SameMeshForOneAndTwoThreads)
{
  const cbc3d::LabelImage image = Ball(24, 9.0, 2, Eigen::Vector3d(1, 1, 2), Eigen::Matrix3d::Identity(),
    Eigen::Vector3d(3, 4, 5));
  cbc3d::LatticeParams params;
  params.EdgeLength = 2.5;
  cbc3d::TetMesh one, two;
  params.NumberOfThreads = 1;
  ASSERT_TRUE(cbc3d::BuildBCCLattice(image, params, one).IsOk());
  params.NumberOfThreads = 2;
  ASSERT_TRUE(cbc3d::BuildBCCLattice(image, params, two).IsOk());
  EXPECT_EQ(one.Tets, two.Tets);
  EXPECT_EQ(one.Labels, two.Labels);
  ASSERT_EQ(one.Points.size(), two.Points.size());
  for (std::size_t i = 0; i < one.Points.size(); ++i)
    EXPECT_EQ(one.Points[i], two.Points[i]);
}

TEST(BCCLattice, RefusesBadEdgeLengthsAndStopsWhenAsked)
{
  const cbc3d::LabelImage image = Ball(16, 5.0, 1, Eigen::Vector3d::Ones(), Eigen::Matrix3d::Identity(),
    Eigen::Vector3d::Zero());
  cbc3d::TetMesh mesh;
  cbc3d::LatticeParams params;
  params.EdgeLength = -1.0;
  EXPECT_NE(cbc3d::BuildBCCLattice(image, params, mesh).GetMessage().find("positive"), std::string::npos);
  params.EdgeLength = 1e-4; // about 10^15 cubes
  const cbc3d::Status tooSmall = cbc3d::BuildBCCLattice(image, params, mesh);
  EXPECT_NE(tooSmall.GetMessage().find("memory"), std::string::npos) << tooSmall.GetMessage();
  params.EdgeLength = 1e308; // far larger than the image: refused at once, not sampled for ever
  const cbc3d::Status tooLarge = cbc3d::BuildBCCLattice(image, params, mesh);
  EXPECT_NE(tooLarge.GetMessage().find("larger than the image"), std::string::npos) << tooLarge.GetMessage();
  params.EdgeLength = cbc3d::MaximumLatticeEdgeLength(image); // 16 mm: a few tets, quickly
  EXPECT_TRUE(cbc3d::BuildBCCLattice(image, params, mesh).IsOk());
  EXPECT_GT(mesh.Tets.size(), 0u);
  params.EdgeLength = 1.0;
  const cbc3d::Status stopped =
    cbc3d::BuildBCCLattice(image, params, mesh, [](double) { return false; });
  EXPECT_TRUE(stopped.WasAborted());
}

TEST(BCCLattice, DefaultEdgeIsEightFinestSpacings)
{
  cbc3d::LabelImage image;
  image.Spacing = Eigen::Vector3d(0.859, 0.859, 2.5);
  EXPECT_DOUBLE_EQ(cbc3d::DefaultLatticeEdgeLength(image), 8 * 0.859);
}

// The ring round a lattice: every lattice tet sharing a vertex with one of the lattice's, as
// background, so that no vertex of the lattice stays on the mesh boundary; the lattice's own
// tets and points come first, unchanged. A mesh that is not this image's lattice is refused.
TEST(BCCLattice, BackgroundRingClosesEveryLatticeVertexsStar)
{
  const cbc3d::LabelImage image = Ball(24, 7.0, 1, Eigen::Vector3d(1.0, 0.8, 1.2),
    Eigen::Matrix3d(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(-3.0, 2.0, 5.0));
  const cbc3d::TetMesh lattice = Lattice(image, 3.0);
  cbc3d::TetMesh ringed = lattice;
  ASSERT_TRUE(cbc3d::AddBackgroundRing(image, ringed));
  ASSERT_GT(ringed.Tets.size(), lattice.Tets.size());
  for (std::size_t t = 0; t < lattice.Tets.size(); ++t)
    ASSERT_EQ(ringed.Tets[t], lattice.Tets[t]);
  for (std::size_t p = 0; p < lattice.Points.size(); ++p)
    ASSERT_EQ(ringed.Points[p], lattice.Points[p]);
  for (std::size_t t = lattice.Tets.size(); t < ringed.Tets.size(); ++t)
  {
    const auto& tet = ringed.Tets[t];
    EXPECT_EQ(ringed.Labels[t], 0);
    EXPECT_GT(cbc3d::SignedVolume(ringed.Points[tet[0]], ringed.Points[tet[1]], ringed.Points[tet[2]],
                ringed.Points[tet[3]]), 0.0);
    EXPECT_TRUE(std::any_of(tet.begin(), tet.end(), [&](cbc3d::PointId v) { return v < cbc3d::PointId(lattice.Points.size()); }))
      << "tet " << t << " shares no vertex with the lattice";
  }
  // Conforming (a face in at most two tets), and no lattice vertex on a boundary face.
  const auto across = cbc3d::FaceNeighbours(ringed.Tets, ringed.Points.size());
  std::map<std::array<cbc3d::PointId, 3>, int> faces;
  for (std::size_t t = 0; t < ringed.Tets.size(); ++t)
    for (int f = 0; f < 4; ++f)
    {
      std::array<cbc3d::PointId, 3> face;
      for (int v = 0, n = 0; v < 4; ++v)
        if (v != f)
          face[n++] = ringed.Tets[t][v];
      std::sort(face.begin(), face.end());
      ASSERT_LE(++faces[face], 2);
      if (across[t][f] < 0)
        for (const cbc3d::PointId v : face)
          ASSERT_GE(v, cbc3d::PointId(lattice.Points.size())) << "a lattice vertex on the boundary, tet " << t;
    }
  // Not this image's lattice: a point moved off the lattice, or another lattice size's frame.
  cbc3d::TetMesh moved = lattice;
  moved.Points[0] += Eigen::Vector3d(0.3, 0.0, 0.0);
  EXPECT_FALSE(cbc3d::AddBackgroundRing(image, moved));
  EXPECT_EQ(moved.Tets.size(), lattice.Tets.size());
  cbc3d::TetMesh other = Lattice(image, 3.0);
  cbc3d::LabelImage shifted = image;
  shifted.Origin += Eigen::Vector3d(0.5, 0.0, 0.0);
  EXPECT_FALSE(cbc3d::AddBackgroundRing(shifted, other));
  EXPECT_EQ(other.Tets.size(), lattice.Tets.size());
}
