// The tagged mesh (boundary and interface triangles with the labels on their sides) on meshes
// whose surfaces are known: unit cubes of Kuhn tets, a cube face being two triangles.
#include "TestMeshes.h"

#include "cbc3d/base/TaggedMesh.h"
#include "cbc3d/base/TetGeometry.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

namespace
{
using namespace cbc3d;

// Two unit cubes side by side along x: tissue 1 at x in [0, 1], tissue 2 at x in [1, 2].
TetMesh TwoCubes()
{
  return cbc3d::testing::KuhnGrid(
    2, 1, 1, [](int, int, int) { return true; }, [](int x, int, int, int) { return x + 1; });
}

// The area-weighted normals of a surface's triangles, summed: (p1 - p0) x (p2 - p0) / 2 each.
Eigen::Vector3d AreaVector(const TaggedMesh& mesh, std::size_t s)
{
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t t = mesh.SurfaceStart[s]; t < mesh.SurfaceStart[s + 1]; ++t)
  {
    const auto& p = mesh.Triangles[t].Points;
    sum += 0.5 * (mesh.Points[p[1]] - mesh.Points[p[0]]).cross(mesh.Points[p[2]] - mesh.Points[p[0]]);
  }
  return sum;
}

double Area(const TaggedMesh& mesh, std::size_t s)
{
  double area = 0.0;
  for (std::size_t t = mesh.SurfaceStart[s]; t < mesh.SurfaceStart[s + 1]; ++t)
  {
    const auto& p = mesh.Triangles[t].Points;
    area += 0.5 * (mesh.Points[p[1]] - mesh.Points[p[0]]).cross(mesh.Points[p[2]] - mesh.Points[p[0]]).norm();
  }
  return area;
}

TEST(TaggedMesh, TwoCubesHaveTwoBoundariesAndOneInterface)
{
  TaggedMesh tagged;
  ASSERT_TRUE(BuildTaggedMesh(TwoCubes(), 0, tagged).IsOk());
  ASSERT_EQ(tagged.Tissues, (std::vector<std::int32_t>{ 1, 2 }));
  ASSERT_EQ(tagged.Surfaces.size(), 3u);
  // Boundaries first, then interfaces; ids 1, 2, 3 in that order.
  const std::vector<std::string> names = { "boundary_1", "boundary_2", "interface_1_2" };
  const std::vector<std::array<std::int32_t, 2>> sides = { { 1, 0 }, { 2, 0 }, { 1, 2 } };
  const std::vector<std::size_t> triangles = { 10, 10, 2 }; // 5, 5 and 1 cube faces
  const std::vector<double> areas = { 5.0, 5.0, 1.0 };
  for (std::size_t s = 0; s < 3; ++s)
  {
    EXPECT_EQ(tagged.Surfaces[s].Name, names[s]);
    EXPECT_EQ(tagged.Surfaces[s].Sides, sides[s]);
    EXPECT_EQ(tagged.Surfaces[s].Id, static_cast<int>(s) + 1);
    EXPECT_EQ(tagged.Surfaces[s].Boundary, s < 2);
    EXPECT_EQ(tagged.SurfaceStart[s + 1] - tagged.SurfaceStart[s], triangles[s]);
    EXPECT_NEAR(Area(tagged, s), areas[s], 1e-12);
    for (std::size_t t = tagged.SurfaceStart[s]; t < tagged.SurfaceStart[s + 1]; ++t)
      EXPECT_EQ(tagged.Triangles[t].Sides, sides[s]);
  }
  EXPECT_EQ(TetsPerTissue(tagged), (std::vector<std::size_t>{ 6, 6 }));
  EXPECT_EQ(FindSurface(tagged, { 1, 2 }), 2);
  EXPECT_EQ(FindSurface(tagged, { 2, 1 }), -1);
}

TEST(TaggedMesh, NormalsPointFromTheFirstSideIntoTheSecond)
{
  TaggedMesh tagged;
  ASSERT_TRUE(BuildTaggedMesh(TwoCubes(), 0, tagged).IsOk());
  // Cube 1's open box misses its +x face, so its outward normals sum to -x; cube 2's to +x.
  // The interface's normals all point from tissue 1 (x < 1) into tissue 2.
  EXPECT_LT((AreaVector(tagged, 0) - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((AreaVector(tagged, 1) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((AreaVector(tagged, 2) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
  const Eigen::Vector3d centre(1.0, 0.5, 0.5);
  for (const TaggedTriangle& triangle : tagged.Triangles)
  {
    const auto& p = tagged.Points;
    const auto& v = triangle.Points;
    const Eigen::Vector3d normal = (p[v[1]] - p[v[0]]).cross(p[v[2]] - p[v[0]]);
    // The triangle is a face of its tet, which lies behind it, and on its first side.
    const Tet& tet = tagged.Tets[triangle.Tet];
    PointId opposite = -1;
    for (const PointId q : tet)
      if (q != v[0] && q != v[1] && q != v[2])
        opposite = q;
    ASSERT_GE(opposite, 0);
    EXPECT_LT(SignedVolume(p[v[0]], p[v[1]], p[v[2]], p[opposite]), 0.0);
    EXPECT_EQ(tagged.Labels[triangle.Tet], triangle.Sides[0]);
    if (triangle.Sides[1] == 0)
      EXPECT_GT(normal.dot(p[v[0]] - centre), 0.0); // boundaries face out of the box
  }
}

TEST(TaggedMesh, InterfaceInsideACubeAlongItsDiagonal)
{
  // One cube, tets 0-2 tissue 3 and 3-5 tissue 7: they meet on two triangles through the
  // diagonal, each of area |(1,1,1) x (1,1,0)| / 2 = sqrt(2) / 2.
  const TetMesh mesh = cbc3d::testing::KuhnGrid(
    1, 1, 1, [](int, int, int) { return true; }, [](int, int, int, int t) { return t < 3 ? 3 : 7; });
  TaggedMesh tagged;
  ASSERT_TRUE(BuildTaggedMesh(mesh, -1, tagged).IsOk());
  const int interface = FindSurface(tagged, { 3, 7 });
  ASSERT_EQ(interface, 2);
  EXPECT_EQ(tagged.Surfaces[interface].Name, "interface_3_7");
  EXPECT_EQ(tagged.SurfaceStart[interface + 1] - tagged.SurfaceStart[interface], 2u);
  EXPECT_NEAR(Area(tagged, interface), std::sqrt(2.0), 1e-12);
  EXPECT_EQ(tagged.Surfaces[0].Name, "boundary_3");
  EXPECT_EQ(tagged.Surfaces[0].Sides, (std::array<std::int32_t, 2>{ 3, -1 }));
  EXPECT_NEAR(Area(tagged, 0) + Area(tagged, 1), 6.0, 1e-12);
}

TEST(TaggedMesh, RejectsAnOutsideLabelThatIsATissue)
{
  TaggedMesh tagged;
  const Status status = BuildTaggedMesh(TwoCubes(), 2, tagged);
  ASSERT_FALSE(status.IsOk());
  EXPECT_NE(status.GetMessage().find("outside label 2"), std::string::npos);
}

TEST(TaggedMesh, RejectsAFaceWithThreeTets)
{
  TetMesh mesh = cbc3d::testing::OneTet();
  mesh.Points.emplace_back(0.2, 0.2, -1.0);
  mesh.Points.emplace_back(0.2, 0.2, -2.0);
  cbc3d::testing::AddTet(mesh, { 0, 1, 2, 4 });
  cbc3d::testing::AddTet(mesh, { 0, 1, 2, 5 });
  TaggedMesh tagged;
  const Status status = BuildTaggedMesh(mesh, 0, tagged);
  ASSERT_FALSE(status.IsOk());
  EXPECT_NE(status.GetMessage().find("does not conform"), std::string::npos);
}
} // namespace
