// The faces of a tet mesh: counts with known answers on a grid of cubes, and the same list for
// any number of threads and any vertex numbering inside the tets.
#include "TestMeshes.h"

#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/PointTets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <map>

namespace
{
// A block of n^3 cubes, six Kuhn tets each.
cbc3d::TetMesh Block(int n)
{
  return cbc3d::testing::KuhnGrid(
    n, n, n, [](int, int, int) { return true; }, [](int, int, int, int) { return 1; });
}
} // namespace

TEST(MeshFaces, ABlockOfCubesHasTheFacesCountingGivesIt)
{
  const int n = 5;
  const cbc3d::TetMesh mesh = Block(n);
  const auto faces = cbc3d::FindMeshFaces(mesh);
  // Each cube has 6 interior faces and 6 square sides of 2 triangles; a side is shared by two
  // cubes unless it lies on the block's boundary (6 n^2 squares).
  const std::size_t boundary = 2 * 6 * n * n;
  const std::size_t squares = 3 * n * n * (n + 1);
  EXPECT_EQ(faces.size(), 6u * n * n * n + 2 * squares);
  std::size_t onBoundary = 0;
  for (const auto& face : faces)
  {
    ASSERT_TRUE(face.Points[0] < face.Points[1] && face.Points[1] < face.Points[2]);
    ASSERT_TRUE(face.TetCount == 1 || face.TetCount == 2);
    onBoundary += face.TetCount == 1;
    if (face.TetCount == 2)
    {
      EXPECT_LT(face.Tets[0], face.Tets[1]);
    }
  }
  EXPECT_EQ(onBoundary, boundary);
}

TEST(MeshFaces, TheListIsTheSameForAnyThreadsAndMatchesAMapOfFaces)
{
  cbc3d::TetMesh mesh = Block(7);
  // Rotate each tet's vertices differently: faces must not depend on the order inside a tet.
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    std::rotate(mesh.Tets[t].begin(), mesh.Tets[t].begin() + t % 4, mesh.Tets[t].end());
  }
  std::map<std::array<cbc3d::PointId, 3>, std::vector<std::int64_t>> expected;
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    for (int skip = 0; skip < 4; ++skip)
    {
      std::array<cbc3d::PointId, 3> face;
      for (int i = 0, k = 0; i < 4; ++i)
      {
        if (i != skip)
        {
          face[k++] = mesh.Tets[t][i];
        }
      }
      std::sort(face.begin(), face.end());
      expected[face].push_back(static_cast<std::int64_t>(t));
    }
  }
  const auto serial = cbc3d::FindMeshFaces(mesh, 1);
  ASSERT_EQ(serial.size(), expected.size());
  auto it = expected.begin();
  for (const auto& face : serial)
  {
    ASSERT_EQ(face.Points, it->first);
    ASSERT_EQ(face.TetCount, static_cast<int>(it->second.size()));
    for (int side = 0; side < face.TetCount; ++side)
    {
      EXPECT_EQ(face.Tets[side], it->second[side]);
    }
    ++it;
  }
  for (const int threads : { 2, 3, 4 })
  {
    const auto parallel = cbc3d::FindMeshFaces(mesh, threads);
    ASSERT_EQ(parallel.size(), serial.size());
    for (std::size_t f = 0; f < serial.size(); ++f)
    {
      ASSERT_EQ(parallel[f].Points, serial[f].Points);
      ASSERT_EQ(parallel[f].Tets, serial[f].Tets);
      ASSERT_EQ(parallel[f].TetCount, serial[f].TetCount);
    }
  }
}

TEST(MeshFaces, ATetOverlappingAnotherMakesAFaceOfThree)
{
  cbc3d::TetMesh mesh = cbc3d::testing::OneTet();
  mesh.Points.emplace_back(0.2, 0.2, -1.0);
  mesh.Points.emplace_back(0.3, 0.3, -2.0);
  cbc3d::testing::AddTet(mesh, { 0, 1, 2, 4 });
  cbc3d::testing::AddTet(mesh, { 0, 1, 2, 5 });
  const auto faces = cbc3d::FindMeshFaces(mesh, 2);
  const auto shared = std::find_if(faces.begin(), faces.end(),
    [](const cbc3d::MeshFace& face) { return face.Points == std::array<cbc3d::PointId, 3>{ 0, 1, 2 }; });
  ASSERT_NE(shared, faces.end());
  EXPECT_EQ(shared->TetCount, 3);
  EXPECT_EQ(faces.size(), 10u);
}

TEST(MeshFaces, SelectingKeepsTheListsOrder)
{
  const cbc3d::TetMesh mesh = Block(4);
  const auto faces = cbc3d::FindMeshFaces(mesh, 1);
  // Every other boundary face, picked by its points: the full list filtered is the answer.
  const auto pick = [](const cbc3d::MeshFace& face) {
    return face.TetCount == 1 && (face.Points[0] + face.Points[1] + face.Points[2]) % 2 == 0;
  };
  std::vector<cbc3d::MeshFace> expected;
  std::copy_if(faces.begin(), faces.end(), std::back_inserter(expected), pick);
  ASSERT_GT(expected.size(), 10u);
  ASSERT_LT(expected.size(), faces.size() / 2);
  for (const int threads : { 1, 2, 3 })
  {
    const auto selected = cbc3d::SelectMeshFaces(mesh.Tets, mesh.Points.size(), threads, pick);
    ASSERT_EQ(selected.size(), expected.size());
    for (std::size_t i = 0; i < selected.size(); ++i)
    {
      EXPECT_EQ(selected[i].Points, expected[i].Points);
      EXPECT_EQ(selected[i].Tets, expected[i].Tets);
      EXPECT_EQ(selected[i].TetCount, expected[i].TetCount);
    }
  }
}

TEST(MeshFaces, PointsWithoutTetsHaveNoFaces)
{
  const std::vector<cbc3d::Tet> none;
  EXPECT_TRUE(cbc3d::FindMeshFaces(none, 5, 2).empty());
  EXPECT_TRUE(cbc3d::SelectMeshFaces(none, 5, 2, [](const cbc3d::MeshFace&) { return true; }).empty());
  EXPECT_TRUE(cbc3d::FaceNeighbours(none, 5, 2).empty());
}

TEST(MeshFaces, FaceNeighboursAreTheTetsSharingEachFaceOrNoneWhereThreeDo)
{
  // A grid of 6 x 5 x 4 Kuhn cubes, against a search of every pair of tets.
  const cbc3d::TetMesh mesh = cbc3d::testing::KuhnGrid(
    6, 5, 4, [](int, int, int) { return true; }, [](int, int, int, int) { return 1; });
  const auto shares = [](const cbc3d::Tet& tet, const cbc3d::Tet& other, int opposite) {
    for (int j = 0; j < 4; ++j)
      if (j != opposite && std::find(other.begin(), other.end(), tet[j]) == other.end())
        return false;
    return true;
  };
  for (const int threads : { 1, 3 })
  {
    const auto across = cbc3d::FaceNeighbours(mesh.Tets, mesh.Points.size(), threads);
    ASSERT_EQ(across.size(), mesh.Tets.size());
    std::size_t boundary = 0;
    for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
      for (int i = 0; i < 4; ++i)
      {
        std::int64_t expected = -1;
        for (std::size_t u = 0; u < mesh.Tets.size(); ++u)
          if (u != t && shares(mesh.Tets[t], mesh.Tets[u], i))
            expected = static_cast<std::int64_t>(u);
        EXPECT_EQ(across[t][i], expected) << "tet " << t << " face " << i;
        boundary += expected < 0 ? 1 : 0;
      }
    EXPECT_EQ(boundary, 2u * (6 * 5 + 5 * 4 + 6 * 4) * 2); // two triangles a boundary square
  }
  // Three tets on one face: it has no neighbour across for any of them.
  const std::vector<cbc3d::Tet> fan = { { 0, 1, 2, 3 }, { 0, 1, 2, 4 }, { 0, 1, 2, 5 } };
  const auto across = cbc3d::FaceNeighbours(fan, 6, 2);
  for (const auto& faces : across)
    EXPECT_EQ(faces[3], -1);
}

TEST(MeshFaces, SelectingOverASubsetGivesTheFacesOfThoseTetsByTheirIds)
{
  const cbc3d::TetMesh mesh = cbc3d::testing::KuhnGrid(
    5, 4, 3, [](int, int, int) { return true; }, [](int i, int, int, int) { return i < 2 ? 1 : 2; });
  std::vector<std::int32_t> subset;
  std::vector<cbc3d::Tet> copied;
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
    if (mesh.Labels[t] == 2)
    {
      subset.push_back(static_cast<std::int32_t>(t));
      copied.push_back(mesh.Tets[t]);
    }
  ASSERT_GT(subset.size(), 0u);
  ASSERT_LT(subset.size(), mesh.Tets.size());
  const auto every = [](const cbc3d::MeshFace&) { return true; };
  const auto expected = cbc3d::SelectMeshFaces(copied, mesh.Points.size(), 1, every);
  for (const int threads : { 1, 3 })
  {
    const auto selected = cbc3d::SelectMeshFaces(mesh.Tets, subset, mesh.Points.size(), threads, every);
    ASSERT_EQ(selected.size(), expected.size());
    for (std::size_t f = 0; f < selected.size(); ++f)
    {
      EXPECT_EQ(selected[f].Points, expected[f].Points);
      EXPECT_EQ(selected[f].TetCount, expected[f].TetCount);
      for (int side = 0; side < expected[f].TetCount; ++side)
        EXPECT_EQ(selected[f].Tets[side], subset[expected[f].Tets[side]]);
    }
  }
}

TEST(PointTets, EachPointListsItsTetsAscendingOnAnyThreads)
{
  // A block of 9^3 cubes: an inner vertex of the Kuhn grid lies in 24 tets, a corner in 1 or 6.
  const cbc3d::TetMesh mesh = Block(9);
  std::vector<std::vector<std::int32_t>> expected(mesh.Points.size());
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
    for (const cbc3d::PointId p : mesh.Tets[t])
      expected[p].push_back(static_cast<std::int32_t>(t));
  std::size_t most = 0;
  for (const auto& tets : expected)
    most = std::max(most, tets.size());
  EXPECT_EQ(most, 24u);
  for (const int threads : { 1, 2, 4 })
  {
    const cbc3d::PointTets around(mesh.Tets, mesh.Points.size(), threads);
    ASSERT_EQ(around.Start.size(), mesh.Points.size() + 1);
    for (std::size_t p = 0; p < mesh.Points.size(); ++p)
    {
      const std::vector<std::int32_t> listed(
        around.Tets.begin() + around.Start[p], around.Tets.begin() + around.Start[p + 1]);
      ASSERT_EQ(listed, expected[p]) << "point " << p << ", " << threads << " threads";
    }
  }
}
