// Surface ears and interior smoothing: the two mesh clean-ups that help deformation.
#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/TetGeometry.h"
#include "cbc3d/deformation/InteriorSmoothing.h"
#include "cbc3d/refinement/SurfaceEars.h"

#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace
{
// The unit cube split into the six Kuhn tets along its diagonal 0-7 (points: bit 0 = x,
// bit 1 = y, bit 2 = z); every corner is in two tets or more.
cbc3d::TetMesh KuhnCube()
{
  cbc3d::TetMesh mesh;
  for (int c = 0; c < 8; ++c)
    mesh.Points.emplace_back(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  const int paths[6][2] = { { 1, 3 }, { 1, 5 }, { 2, 3 }, { 2, 6 }, { 4, 5 }, { 4, 6 } };
  for (const auto& path : paths)
  {
    cbc3d::Tet tet = { 0, path[0], path[1], 7 };
    if (cbc3d::SignedVolume(mesh.Points[tet[0]], mesh.Points[tet[1]], mesh.Points[tet[2]], mesh.Points[tet[3]]) < 0)
      std::swap(tet[1], tet[2]);
    mesh.Tets.push_back(tet);
    mesh.Labels.push_back(1);
  }
  return mesh;
}

bool IsTissue(std::int32_t label)
{
  return label > 0;
}
} // namespace

TEST(SurfaceEars, AnEarOnACubeFaceGoesAndTheCubeStays)
{
  cbc3d::TetMesh mesh = KuhnCube();
  // The ear: the triangle 1, 3, 7 of the face x = 1 (a face of cube tet 0, 1, 3, 7) and a
  // new tip outside.
  mesh.Points.emplace_back(1.5, 0.7, 0.4);
  mesh.Tets.push_back({ 1, 3, 7, 8 });
  ASSERT_GT(cbc3d::SignedVolume(mesh.Points[1], mesh.Points[3], mesh.Points[7], mesh.Points[8]), 0.0);
  mesh.Labels.push_back(1);
  std::vector<std::int32_t> labels = mesh.Labels;
  EXPECT_EQ(cbc3d::RemoveSurfaceEars(mesh.Tets, cbc3d::FaceNeighbours(mesh.Tets, mesh.Points.size()), mesh.Points.size(), labels, IsTissue, 0), 1u);
  EXPECT_EQ(labels.back(), 0);
  EXPECT_TRUE(std::all_of(labels.begin(), labels.end() - 1, [](std::int32_t l) { return l == 1; }));

  // An ear of another tissue sits on an interface, not on a spike: it stays.
  labels = mesh.Labels;
  labels.back() = 2;
  EXPECT_EQ(cbc3d::RemoveSurfaceEars(mesh.Tets, cbc3d::FaceNeighbours(mesh.Tets, mesh.Points.size()), mesh.Points.size(), labels, IsTissue, 0), 0u);
  EXPECT_EQ(labels.back(), 2);
}

TEST(SurfaceEars, ALoneTetStays)
{
  // Every vertex of a lone tet is used once, but no tet of its label holds its base.
  const std::vector<cbc3d::Tet> tets = { { 0, 1, 2, 3 } };
  std::vector<std::int32_t> labels = { 1 };
  EXPECT_EQ(cbc3d::RemoveSurfaceEars(tets, cbc3d::FaceNeighbours(tets, 4), 4, labels, IsTissue, 0), 0u);
  EXPECT_EQ(labels[0], 1);
}

namespace
{
// A cube around a centre point: each face split in two, each half joined to the centre.
cbc3d::TetMesh CubeAroundCentre()
{
  cbc3d::TetMesh mesh;
  for (int c = 0; c < 8; ++c)
    mesh.Points.emplace_back(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  mesh.Points.emplace_back(0.5, 0.5, 0.5); // point 8
  const int faces[6][4] = { { 0, 1, 3, 2 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 3, 7, 6 }, { 0, 2, 6, 4 },
    { 1, 3, 7, 5 } };
  for (const auto& f : faces)
    for (const auto& tri : { std::array<int, 3>{ f[0], f[1], f[2] }, std::array<int, 3>{ f[0], f[2], f[3] } })
    {
      cbc3d::Tet tet = { tri[0], tri[1], tri[2], 8 };
      if (cbc3d::SignedVolume(mesh.Points[tet[0]], mesh.Points[tet[1]], mesh.Points[tet[2]], mesh.Points[tet[3]]) < 0)
        std::swap(tet[1], tet[2]);
      mesh.Tets.push_back(tet);
      mesh.Labels.push_back(1);
    }
  return mesh;
}

double WorstCosine(const cbc3d::TetMesh& mesh, const std::vector<Eigen::Vector3d>& x)
{
  double worst = 0.0;
  for (const auto& t : mesh.Tets)
    worst = std::max(worst, cbc3d::LargestDihedralCosine(x[t[0]], x[t[1]], x[t[2]], x[t[3]]));
  return worst;
}
} // namespace

TEST(InteriorSmoothing, AnOffCentreVertexGoesBackTowardTheCentre)
{
  const cbc3d::TetMesh mesh = CubeAroundCentre();
  std::vector<Eigen::Vector3d> x = mesh.Points;
  x[8] = Eigen::Vector3d(0.9, 0.5, 0.5); // close to face x = 1: thin tets there
  const double before = WorstCosine(mesh, x);
  const cbc3d::InteriorSmoothing smoothing(mesh.Tets, x.size());

  std::vector<char> movable(x.size(), 0);
  EXPECT_EQ(smoothing.Smooth(x, movable, 10), 0u); // nothing may move
  EXPECT_EQ(x[8], Eigen::Vector3d(0.9, 0.5, 0.5));

  movable[8] = 1;
  EXPECT_GT(smoothing.Smooth(x, movable, 10), 0u);
  EXPECT_LT((x[8] - Eigen::Vector3d::Constant(0.5)).norm(), 0.1);
  EXPECT_LT(WorstCosine(mesh, x), before);
  for (int c = 0; c < 8; ++c)
    EXPECT_EQ(x[c], mesh.Points[c]); // only the movable point moved
}

TEST(InteriorSmoothing, ASweepOnThreadsMakesTheMovesOfTheSweepInPointOrder)
{
  // A 6 x 5 x 4 grid of Kuhn cubes, its interior points jiggled: many movable neighbours.
  const cbc3d::TetMesh mesh =
    cbc3d::testing::KuhnGrid(6, 5, 4, [](int, int, int) { return true; }, [](int, int, int, int) { return 1; });
  std::vector<Eigen::Vector3d> start = mesh.Points;
  std::vector<char> movable(start.size(), 0);
  for (std::size_t p = 0; p < start.size(); ++p)
  {
    const Eigen::Vector3d& x = mesh.Points[p];
    const bool inside = x.x() > 0 && x.x() < 6 && x.y() > 0 && x.y() < 5 && x.z() > 0 && x.z() < 4;
    movable[p] = inside;
    if (inside)
      start[p] += 0.3 * Eigen::Vector3d(std::sin(1.0 + p), std::cos(2.0 * p), std::sin(3.0 * p));
  }
  // The sweep itself, in point order, written out: each point goes to the mean of its tets'
  // centroids if its worst tet's largest |cos| gets smaller (inverted counts as 2).
  auto badness = [&](const std::vector<Eigen::Vector3d>& x, const cbc3d::Tet& t) {
    return cbc3d::SignedVolume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]) > 0.0
      ? cbc3d::LargestDihedralCosine(x[t[0]], x[t[1]], x[t[2]], x[t[3]])
      : 2.0;
  };
  std::vector<Eigen::Vector3d> expected = start;
  std::size_t expectedMoves = 0;
  for (int sweep = 0; sweep < 2; ++sweep)
    for (std::size_t p = 0; p < expected.size(); ++p)
    {
      std::vector<cbc3d::Tet> around;
      for (const cbc3d::Tet& tet : mesh.Tets)
        if (std::find(tet.begin(), tet.end(), cbc3d::PointId(p)) != tet.end())
          around.push_back(tet);
      if (!movable[p] || around.empty())
        continue;
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      double before = 0.0;
      for (const cbc3d::Tet& tet : around)
      {
        for (const cbc3d::PointId q : tet)
          centre += expected[q] / (4.0 * around.size());
        before = std::max(before, badness(expected, tet));
      }
      const Eigen::Vector3d kept = expected[p];
      expected[p] = centre;
      double after = 0.0;
      for (const cbc3d::Tet& tet : around)
        after = std::max(after, badness(expected, tet));
      if (after < before)
        ++expectedMoves;
      else
        expected[p] = kept;
    }
  ASSERT_GT(expectedMoves, 50u);

  const cbc3d::InteriorSmoothing smoothing(mesh.Tets, start.size());
  for (const int threads : { 1, 2, 4 })
  {
    std::vector<Eigen::Vector3d> x = start;
    EXPECT_EQ(smoothing.Smooth(x, movable, 2, threads), expectedMoves) << threads << " threads";
    for (std::size_t p = 0; p < x.size(); ++p)
      EXPECT_LT((x[p] - expected[p]).norm(), 1e-12) << "point " << p << ", " << threads << " threads";
  }
}
