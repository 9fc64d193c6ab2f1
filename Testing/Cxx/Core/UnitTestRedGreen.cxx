#include "TestMeshes.h"

#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/TetGeometry.h"
#include "cbc3d/base/TetTopology.h"
#include "cbc3d/lattice/EdgeMidpoints.h"
#include "cbc3d/lattice/RedGreenMesh.h"
#include "cbc3d/lattice/RedGreenTables.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <set>

namespace
{
// A positive, irregular tet and its edge midpoints, in local point order.
std::array<Eigen::Vector3d, 10> LocalPoints()
{
  std::array<Eigen::Vector3d, 10> p = { Eigen::Vector3d(0.1, -0.2, 0.0), Eigen::Vector3d(1.3, 0.1, 0.2),
    Eigen::Vector3d(0.2, 1.1, -0.1), Eigen::Vector3d(0.3, 0.2, 0.9) };
  for (int e = 0; e < 6; ++e)
    p[4 + e] = 0.5 * (p[cbc3d::TetEdges[e][0]] + p[cbc3d::TetEdges[e][1]]);
  return p;
}

double Volume(const std::array<Eigen::Vector3d, 10>& p, const cbc3d::LocalTet& t)
{
  return cbc3d::SignedVolume(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
}

// Child triangles lying on parent face f (all three points on that face), as sorted triples.
std::set<std::array<int, 3>> TrianglesOnFace(const std::vector<cbc3d::LocalTet>& children, int f)
{
  std::set<int> onFace(cbc3d::TetFaces[f].begin(), cbc3d::TetFaces[f].end());
  for (int e = 0; e < 6; ++e)
    if (onFace.count(cbc3d::TetEdges[e][0]) && onFace.count(cbc3d::TetEdges[e][1]))
      onFace.insert(4 + e);
  // Insert midpoints after the corners so that the test above sees only corners.
  std::set<std::array<int, 3>> triangles;
  for (const auto& child : children)
    for (const auto& face : cbc3d::TetFaces)
    {
      std::array<int, 3> tri = { child[face[0]], child[face[1]], child[face[2]] };
      if (std::all_of(tri.begin(), tri.end(), [&](int v) { return onFace.count(v) > 0; }))
      {
        std::sort(tri.begin(), tri.end());
        triangles.insert(tri);
      }
    }
  return triangles;
}

// Which of face f's edges a mask splits, as a 3-bit pattern.
int FacePattern(std::uint8_t mask, int f)
{
  int pattern = 0, bit = 0;
  for (int e = 0; e < 6; ++e)
  {
    const auto& face = cbc3d::TetFaces[f];
    const bool onFace = std::count(face.begin(), face.end(), cbc3d::TetEdges[e][0]) &&
      std::count(face.begin(), face.end(), cbc3d::TetEdges[e][1]);
    if (onFace)
      pattern |= ((mask >> e) & 1) << bit++;
  }
  return pattern;
}

// Two positive BCC tets sharing a face.
cbc3d::TetMesh TwoBCCTets()
{
  cbc3d::TetMesh roots;
  roots.Points = { { 0.5, 0.5, 0.5 }, { 1.5, 0.5, 0.5 }, { 1, 0, 0 }, { 1, 1, 0 }, { 1, 1, 1 } };
  roots.Tets = { { 0, 1, 2, 3 }, { 0, 1, 3, 4 } };
  for (auto& tet : roots.Tets)
  {
    const auto& p = roots.Points;
    if (cbc3d::SignedVolume(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]) < 0)
      std::swap(tet[2], tet[3]);
  }
  roots.Labels = { 1, 1 };
  return roots;
}
} // namespace

TEST(RedGreenTables, EveryMaskClosesGreenOrUpgradesToRed)
{
  const auto p = LocalPoints();
  const double parent = Volume(p, { 0, 1, 2, 3 });
  ASSERT_GT(parent, 0.0);
  int green = 0;
  for (int mask = 0; mask < 64; ++mask)
  {
    const auto* closure = cbc3d::GreenClosure(static_cast<std::uint8_t>(mask));
    const int splits = __builtin_popcount(mask);
    if (!closure)
    {
      continue;
    }
    ++green;
    double sum = 0.0;
    std::set<int> used;
    for (const auto& child : *closure)
    {
      EXPECT_GT(Volume(p, child), 1e-6) << "mask " << mask;
      sum += Volume(p, child);
      used.insert(child.begin(), child.end());
    }
    EXPECT_NEAR(sum, parent, 1e-12) << "mask " << mask;
    // Every split edge's midpoint is used, no other midpoint is.
    for (int e = 0; e < 6; ++e)
      EXPECT_EQ(used.count(4 + e) > 0, ((mask >> e) & 1) == 1) << "mask " << mask << " edge " << e;
    EXPECT_EQ(closure->size(), splits == 0 ? 1u : splits == 1 ? 2u : 4u) << "mask " << mask;
  }
  // None, 6 single edges, 3 opposite pairs, 4 faces.
  EXPECT_EQ(green, 14);
}

TEST(RedGreenTables, RedChildrenFillTheParentAndHaveEqualVolume)
{
  const auto p = LocalPoints();
  const double parent = Volume(p, { 0, 1, 2, 3 });
  for (int d = 0; d < 3; ++d)
  {
    double sum = 0.0;
    for (const auto& child : cbc3d::RedChildren(d))
    {
      EXPECT_NEAR(Volume(p, child), parent / 8.0, 1e-12);
      sum += Volume(p, child);
    }
    EXPECT_NEAR(sum, parent, 1e-12);
  }
}

TEST(RedGreenTables, AFaceIsSplitTheSameWayWhateverTheRestOfTheTet)
{
  // For each face, every split (green or red) that splits the same edges of that face puts the
  // same triangles on it, so the two tets sharing the face always agree.
  std::map<std::pair<int, int>, std::set<std::array<int, 3>>> seen; // (face, pattern) -> triangles
  auto record = [&](std::uint8_t mask, const std::vector<cbc3d::LocalTet>& children) {
    for (int f = 0; f < 4; ++f)
    {
      const auto triangles = TrianglesOnFace(children, f);
      const auto key = std::make_pair(f, FacePattern(mask, f));
      const auto found = seen.emplace(key, triangles);
      EXPECT_EQ(found.first->second, triangles) << "mask " << int(mask) << " face " << f;
    }
  };
  for (int mask = 0; mask < 64; ++mask)
    if (const auto* closure = cbc3d::GreenClosure(static_cast<std::uint8_t>(mask)))
      record(static_cast<std::uint8_t>(mask), *closure);
  for (int d = 0; d < 3; ++d)
  {
    const auto& red = cbc3d::RedChildren(d);
    record(63, std::vector<cbc3d::LocalTet>(red.begin(), red.end()));
  }
}

TEST(RedGreenMesh, RefinedBCCTetsKeepTheirAnglesAndTheMeshConforms)
{
  // Split one of two BCC tets twice (a child of it too): the closure must split the other as
  // needed and leave no hanging point.
  const cbc3d::TetMesh roots = TwoBCCTets();
  cbc3d::RedGreenMesh mesh(roots);
  mesh.SplitRed(0);
  mesh.SplitRed(2); // the first child of tet 0
  mesh.Close();
  std::vector<cbc3d::Tet> tets;
  std::vector<std::int64_t> source;
  mesh.BuildConforming(tets, source);
  const auto& p = mesh.Points();
  double volume = 0.0;
  std::map<std::array<cbc3d::PointId, 3>, int> faces;
  for (const auto& tet : tets)
  {
    const double v = cbc3d::SignedVolume(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]);
    ASSERT_GT(v, 0.0);
    volume += v;
    auto angles = cbc3d::DihedralAngles(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]);
    for (const double a : angles)
    {
      EXPECT_GE(a * cbc3d::RadiansToDegrees, 30.0 - 1e-9);
      EXPECT_LE(a * cbc3d::RadiansToDegrees, 116.5651 + 1e-4); // arccos(-1/sqrt 5)
    }
    for (const auto& f : cbc3d::TetFaces)
    {
      std::array<cbc3d::PointId, 3> key = { tet[f[0]], tet[f[1]], tet[f[2]] };
      std::sort(key.begin(), key.end());
      ++faces[key];
    }
  }
  const double expected = 2.0 * cbc3d::SignedVolume(roots.Points[0], roots.Points[1], roots.Points[2], roots.Points[3]);
  EXPECT_NEAR(volume, expected, 1e-12);
  // Every face is used once (boundary) or twice; no point lies inside another tet's edge.
  for (const auto& entry : faces)
    EXPECT_LE(entry.second, 2);
  for (std::size_t q = 0; q < p.size(); ++q)
    for (const auto& tet : tets)
      for (const auto& e : cbc3d::TetEdges)
      {
        const Eigen::Vector3d a = p[tet[e[0]]], b = p[tet[e[1]]];
        if (std::find(tet.begin(), tet.end(), cbc3d::PointId(q)) != tet.end())
          continue;
        const double t = (p[q] - a).dot(b - a) / (b - a).squaredNorm();
        const bool onEdge = t > 1e-9 && t < 1 - 1e-9 && (a + t * (b - a) - p[q]).norm() < 1e-9;
        EXPECT_FALSE(onEdge) << "point " << q << " hangs on an edge";
      }
}

TEST(RedGreenMesh, TwoSplitEdgesOfAFaceForceTheThirdNotARedSplit)
{
  // One tet; split edges 01 and 02 (two edges of face 012): the closure splits edge 12 too and
  // the tet becomes the 4-tet green closure of a split face, with no red split.
  cbc3d::TetMesh root;
  root.Points = { { 0, 0, 0 }, { 2, 0, 0 }, { 0, 2, 0 }, { 0, 0, 2 } };
  root.Tets = { { 0, 1, 2, 3 } };
  root.Labels = { 1 };
  cbc3d::RedGreenMesh mesh(root);
  mesh.SplitEdge(0, 1);
  mesh.SplitEdge(0, 2);
  mesh.Close();
  EXPECT_EQ(mesh.Reds().size(), 1u); // no red split
  std::vector<cbc3d::Tet> tets;
  std::vector<std::int64_t> source;
  mesh.BuildConforming(tets, source);
  ASSERT_EQ(tets.size(), 4u);
  ASSERT_EQ(mesh.Points().size(), 7u); // the corners and the three midpoints of face 012
  EXPECT_TRUE(mesh.Points()[6].isApprox(Eigen::Vector3d(1, 1, 0)));
  double volume = 0.0;
  for (const auto& tet : tets)
  {
    const auto& p = mesh.Points();
    const double v = cbc3d::SignedVolume(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]);
    EXPECT_GT(v, 0.0);
    volume += v;
  }
  EXPECT_NEAR(volume, 8.0 / 6.0, 1e-12);

  // Two opposite split edges (01 and 23) have a green closure of their own and stay as they
  // are; three edges at one corner (01, 02, 03) are on no single face and need a red split.
  cbc3d::RedGreenMesh opposite(root);
  opposite.SplitEdge(0, 1);
  opposite.SplitEdge(2, 3);
  opposite.Close();
  EXPECT_EQ(opposite.Reds().size(), 1u);
  EXPECT_EQ(opposite.Points().size(), 6u);
  cbc3d::RedGreenMesh corner(root);
  corner.SplitEdge(0, 1);
  corner.SplitEdge(0, 2);
  corner.SplitEdge(0, 3);
  corner.Close();
  EXPECT_EQ(corner.Reds().size(), 9u); // the root and its 8 red children
}

TEST(RedGreenMesh, ClosingAndBuildingStopWhenAsked)
{
  cbc3d::RedGreenMesh mesh(TwoBCCTets());
  mesh.SplitRed(0);
  mesh.SplitRed(2);
  const auto stop = [] { return false; };
  EXPECT_FALSE(mesh.Close(stop));
  const std::size_t reds = mesh.Reds().size();
  EXPECT_TRUE(mesh.Close([] { return true; }));
  EXPECT_GT(mesh.Reds().size(), reds); // the stop came before the closure's first split
  std::vector<cbc3d::Tet> tets;
  std::vector<std::int64_t> source;
  EXPECT_FALSE(mesh.BuildConforming(tets, source, stop));
  EXPECT_TRUE(mesh.BuildConforming(tets, source, [] { return true; }));
  EXPECT_FALSE(tets.empty());
}

TEST(RedGreenMesh, RepeatedRandomSplitsAndClosuresKeepTheMeshConforming)
{
  // Closing again after more splits re-checks only the leaves near new midpoints: after every
  // round the mesh must still fill the block exactly, with no face inside it left unshared
  // (a point hanging on an edge or a face leaves such faces) and none shared by three tets.
  const int n = 3;
  const cbc3d::TetMesh roots = cbc3d::testing::KuhnGrid(
    n, n, n, [](int, int, int) { return true; }, [](int, int, int, int) { return 1; });
  cbc3d::RedGreenMesh mesh(roots);
  std::mt19937 random(7);
  for (int round = 0; round < 6; ++round)
  {
    const std::size_t reds = mesh.Reds().size();
    for (int split = 0; split < 3; ++split)
    {
      const std::size_t red = random() % reds;
      if (mesh.Reds()[red].Leaf && mesh.Reds()[red].Level < 3)
      {
        mesh.SplitRed(red);
      }
    }
    const std::size_t red = random() % reds;
    if (mesh.Reds()[red].Leaf && mesh.Reds()[red].Level < 3)
    {
      const cbc3d::Tet& tet = mesh.Reds()[red].Points;
      mesh.SplitEdge(tet[0], tet[1 + random() % 3]);
    }
    ASSERT_TRUE(mesh.Close());

    std::vector<cbc3d::Tet> tets;
    std::vector<std::int64_t> source;
    ASSERT_TRUE(mesh.BuildConforming(tets, source));
    const auto& p = mesh.Points();
    double volume = 0.0;
    for (const auto& tet : tets)
    {
      volume += cbc3d::SignedVolume(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]);
    }
    EXPECT_NEAR(volume, n * n * n, 1e-9) << "round " << round;
    double boundaryArea = 0.0;
    for (const auto& face : cbc3d::FindMeshFaces(tets, p.size()))
    {
      ASSERT_LE(face.TetCount, 2) << "round " << round;
      if (face.TetCount == 1)
      {
        const auto& q = face.Points;
        boundaryArea += 0.5 * (p[q[1]] - p[q[0]]).cross(p[q[2]] - p[q[0]]).norm();
      }
    }
    EXPECT_NEAR(boundaryArea, 6.0 * n * n, 1e-9) << "round " << round;
  }
}

TEST(EdgeMidpoints, FindsWhatWasStoredThroughGrowthAndNothingElse)
{
  cbc3d::EdgeMidpoints table;
  std::mt19937_64 random(3);
  std::map<std::uint64_t, cbc3d::PointId> expected;
  for (cbc3d::PointId point = 0; point < 50000; ++point)
  {
    const std::uint64_t a = random() % 100000, b = a + 1 + random() % 1000;
    const std::uint64_t key = (a << 32) | b;
    const auto [stored, inserted] = table.Insert(key, point);
    const auto [it, fresh] = expected.emplace(key, point);
    EXPECT_EQ(inserted, fresh);
    EXPECT_EQ(stored, it->second);
  }
  EXPECT_EQ(table.Size(), expected.size());
  for (const auto& [key, point] : expected)
  {
    ASSERT_EQ(table.Find(key), point);
  }
  EXPECT_EQ(table.Find((std::uint64_t{ 200000 } << 32) | 200001), -1);
}

TEST(RedGreenMesh, ALeafWithTheSameMaskBuildsTheSameTets)
{
  // Refinement takes over the samples of a leaf whose split edges did not change between two
  // builds: such a leaf must make the same tets, in the same order; a leaf whose mask changed
  // is reported with its new mask, and a red split is no longer a leaf.
  const cbc3d::TetMesh roots = cbc3d::testing::KuhnGrid(
    3, 3, 3, [](int, int, int) { return true; }, [](int, int, int, int) { return 1; });
  cbc3d::RedGreenMesh mesh(roots);
  mesh.Close();
  std::vector<cbc3d::Tet> before, after;
  std::vector<std::int64_t> sourceBefore, sourceAfter;
  std::vector<std::uint8_t> masksBefore, masksAfter;
  ASSERT_TRUE(mesh.BuildConforming(before, sourceBefore, nullptr, &masksBefore));
  mesh.SplitRed(40);
  mesh.Close();
  ASSERT_TRUE(mesh.BuildConforming(after, sourceAfter, nullptr, &masksAfter));
  ASSERT_EQ(masksAfter.size(), mesh.Reds().size());
  EXPECT_EQ(masksAfter[40], cbc3d::RedGreenMesh::NotLeaf);
  auto tetsOf = [](std::int64_t red, const std::vector<cbc3d::Tet>& tets, const std::vector<std::int64_t>& source) {
    std::vector<cbc3d::Tet> of;
    for (std::size_t t = 0; t < tets.size(); ++t)
      if (source[t] == red)
        of.push_back(tets[t]);
    return of;
  };
  int same = 0, changed = 0;
  for (std::size_t red = 0; red < masksBefore.size(); ++red)
  {
    if (masksAfter[red] == cbc3d::RedGreenMesh::NotLeaf)
      continue;
    const auto now = tetsOf(std::int64_t(red), after, sourceAfter);
    EXPECT_EQ(now.size(), cbc3d::GreenClosure(masksAfter[red])->size()) << "red " << red;
    if (masksAfter[red] == masksBefore[red])
    {
      EXPECT_EQ(now, tetsOf(std::int64_t(red), before, sourceBefore)) << "red " << red;
      ++same;
    }
    else
    {
      EXPECT_NE(masksAfter[red], 0) << "red " << red; // it has split edges now
      ++changed;
    }
  }
  EXPECT_GT(same, 0);
  EXPECT_GT(changed, 0); // the split's neighbours took green closures
}

TEST(RedGreenMesh, TheConformingMeshFillsTheGridAndIsTheSameOnAnyNumberOfThreads)
{
  // A 4x4x4 grid of unit cubes (64 mm^3) with reds split at three levels: the leaves' children
  // must tile it exactly, in the order of the reds, whatever the number of threads.
  const cbc3d::TetMesh roots = cbc3d::testing::KuhnGrid(
    4, 4, 4, [](int, int, int) { return true; }, [](int, int, int, int) { return 1; });
  cbc3d::RedGreenMesh mesh(roots);
  for (const std::size_t red : { std::size_t(7), std::size_t(100), std::size_t(250) })
  {
    mesh.SplitRed(red);
    mesh.Close();
  }
  mesh.SplitRed(mesh.Reds().size() - 3); // a child of the last split: a third level
  mesh.Close();
  std::vector<cbc3d::Tet> serial, parallel;
  std::vector<std::int64_t> serialSource, parallelSource;
  std::vector<std::uint8_t> serialMasks, parallelMasks;
  ASSERT_TRUE(mesh.BuildConforming(serial, serialSource, nullptr, &serialMasks, 1));
  ASSERT_TRUE(mesh.BuildConforming(parallel, parallelSource, nullptr, &parallelMasks, 3));
  EXPECT_EQ(serial, parallel);
  EXPECT_EQ(serialSource, parallelSource);
  EXPECT_EQ(serialMasks, parallelMasks);
  EXPECT_TRUE(std::is_sorted(serialSource.begin(), serialSource.end()));
  EXPECT_GT(serial.size(), roots.Tets.size());
  double volume = 0.0;
  for (const cbc3d::Tet& tet : serial)
  {
    const double v = cbc3d::SignedVolume(mesh.Points()[tet[0]], mesh.Points()[tet[1]],
      mesh.Points()[tet[2]], mesh.Points()[tet[3]]);
    EXPECT_GT(std::abs(v), 0.0);
    volume += std::abs(v);
  }
  EXPECT_NEAR(volume, 64.0, 1e-9);
}
