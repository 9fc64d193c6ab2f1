// The manifold repair on voxel patterns whose cubes are split into tets: each cube votes for
// its voxel's label, so the pattern's hinges (cubes meeting along an edge or at a corner) are
// the mesh's before the repair. After it, the topology measure (MeshTopology, written apart
// from the repair) must find every tissue and the whole body manifold.
#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/quality/MeshTopology.h"
#include "cbc3d/soundlabels/ManifoldRepair.h"
#include "cbc3d/soundlabels/VertexStar.h"

#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <functional>
#include <random>

namespace
{
using cbc3d::testing::KuhnGrid;
using Pattern = std::function<std::int32_t(int, int, int)>;
constexpr std::int32_t Background = 0;

struct Repaired
{
  cbc3d::TetMesh Before;                       // every cube of the box, labelled by the pattern
  std::vector<std::int32_t> Classes;           // after the repair
  cbc3d::ManifoldRepairResult Result;
  std::int64_t NonManifoldBefore = 0, NonManifoldAfter = 0;
};

// The tissue tets alone, as the pipeline hands them on.
cbc3d::TetMesh TissueOnly(const cbc3d::TetMesh& mesh, const std::vector<std::int32_t>& classes)
{
  cbc3d::TetMesh out;
  out.Points = mesh.Points;
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
    if (classes[t] != Background)
    {
      out.Tets.push_back(mesh.Tets[t]);
      out.Labels.push_back(classes[t]);
    }
  return out;
}

// `present` tells which cubes are in the mesh at all (a lattice may leave some out).
Repaired Repair(int n, const Pattern& pattern, const std::function<bool(int, int, int)>& present = nullptr,
  int threads = 1)
{
  Repaired r;
  std::vector<std::int32_t> cubeLabel;
  r.Before = KuhnGrid(
    n, n, n, [&](int x, int y, int z) { return !present || present(x, y, z); },
    [&](int x, int y, int z, int tet) {
      if (tet == 0)
        cubeLabel.push_back(pattern(x, y, z));
      return pattern(x, y, z);
    });
  r.Classes = r.Before.Labels;
  const auto across = cbc3d::FaceNeighbours(r.Before.Tets, r.Before.Points.size());
  const cbc3d::ClassVotes votes = [&](std::int64_t t, std::int32_t cls) {
    return std::int64_t(cubeLabel[t / 6] == cls ? 6 : 0);
  };
  r.NonManifoldBefore = cbc3d::CountNonManifoldVertices(r.Before.Points, r.Before.Tets, across, Background, r.Classes);
  r.Result =
    cbc3d::RepairManifoldLabels(r.Before.Points, r.Before.Tets, across, Background, votes, r.Classes, {}, threads);
  r.NonManifoldAfter = cbc3d::CountNonManifoldVertices(r.Before.Points, r.Before.Tets, across, Background, r.Classes);
  return r;
}

void ExpectManifold(const cbc3d::RegionTopology& r, const char* what)
{
  EXPECT_EQ(r.HingedParts, 0) << what;
  EXPECT_EQ(r.NonManifoldEdges, 0) << what;
  EXPECT_EQ(r.NonManifoldVertices, 0) << what;
}

void ExpectSound(const Repaired& r)
{
  EXPECT_EQ(r.NonManifoldAfter, 0);
  EXPECT_EQ(r.Result.Unrepaired, 0);
  const cbc3d::MeshTopology topology = cbc3d::MeasureMeshTopology(TissueOnly(r.Before, r.Classes));
  ExpectManifold(topology.Whole, "whole");
  for (const auto& [label, tissue] : topology.Tissues)
    ExpectManifold(tissue, "tissue");
  EXPECT_TRUE(topology.SolverReady());
}

bool Inside(int x, int y, int z, int lo, int hi)
{
  return x >= lo && x < hi && y >= lo && y < hi && z >= lo && z < hi;
}
} // namespace

namespace
{
// A star of nodes with these classes, linked along `links`.
cbc3d::VertexStar StarOf(const std::vector<std::int32_t>& classes, const std::vector<std::pair<int, int>>& links)
{
  cbc3d::VertexStar star;
  star.Class = classes;
  star.Links.resize(classes.size());
  for (std::size_t i = 0; i < classes.size(); ++i)
    star.Tets.push_back(std::int64_t(i));
  for (const auto& [a, b] : links)
    cbc3d::LinkNodes(star, a, b);
  return star;
}
} // namespace

TEST(VertexStar, SplitClassesComeFirstThenRingsAndTwoWholeClassesHaveNeither)
{
  cbc3d::StarViolation found;
  const std::vector<std::pair<int, int>> cycle = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 } };
  // Alternating round a cycle: both classes in two parts; the smaller label is named.
  ASSERT_TRUE(cbc3d::FindStarViolation(StarOf({ 2, 1, 2, 1 }, cycle), 0, found));
  EXPECT_TRUE(found.Split);
  EXPECT_EQ(found.Class, 1);
  // Two halves of a cycle: each class one piece, so each one's complement (the other) too.
  EXPECT_FALSE(cbc3d::FindStarViolation(StarOf({ 1, 1, 2, 2 }, cycle), 0, found));
  // A chain A - B - C: every class whole, but B's complement is A and C apart: a ring of B.
  const std::vector<std::pair<int, int>> chain = { { 0, 1 }, { 1, 2 } };
  ASSERT_TRUE(cbc3d::FindStarViolation(StarOf({ 3, 5, 7 }, chain), 0, found));
  EXPECT_FALSE(found.Split);
  EXPECT_EQ(found.Class, 5);
  // The same chain with A again at its end: A is split, which comes before B's ring.
  ASSERT_TRUE(cbc3d::FindStarViolation(StarOf({ 3, 5, 3 }, chain), 0, found));
  EXPECT_TRUE(found.Split);
  EXPECT_EQ(found.Class, 3);
  // Background alone has nothing to repair, however it is cut.
  EXPECT_FALSE(cbc3d::FindStarViolation(StarOf({ 0, 0, 0, 0 }, { { 0, 1 } }), 0, found));
  EXPECT_TRUE(cbc3d::FindStarViolation(StarOf({ 0, 0, 0, 0 }, { { 0, 1 } }), 9, found));
}

TEST(ManifoldRepair, ASolidBlockIsLeftAlone)
{
  const Repaired r = Repair(5, [](int x, int y, int z) { return Inside(x, y, z, 1, 4) ? 1 : 0; });
  EXPECT_EQ(r.NonManifoldBefore, 0);
  EXPECT_EQ(r.Result.Relabelled, 0);
  ExpectSound(r);
}

TEST(ManifoldRepair, CubesOnOneEdgeNoLongerHinge)
{
  const Repaired r = Repair(4, [](int x, int y, int z) {
    return (x == 1 && y == 1 && z == 1) || (x == 2 && y == 2 && z == 1) ? 1 : 0;
  });
  // Before: two pieces joined only along the edge they share.
  EXPECT_EQ(cbc3d::MeasureMeshTopology(TissueOnly(r.Before, r.Before.Labels)).Whole.HingedParts, 1);
  EXPECT_GT(r.NonManifoldBefore, 0);
  ExpectSound(r);
}

TEST(ManifoldRepair, CubesOnOneCornerNoLongerHinge)
{
  const Repaired r = Repair(4, [](int x, int y, int z) {
    return (x == 1 && y == 1 && z == 1) || (x == 2 && y == 2 && z == 2) ? 1 : 0;
  });
  EXPECT_EQ(cbc3d::MeasureMeshTopology(TissueOnly(r.Before, r.Before.Labels)).Whole.HingedParts, 1);
  ExpectSound(r);
}

TEST(ManifoldRepair, TwoTissuesOnOneEdgeNoLongerHinge)
{
  const Repaired r = Repair(4, [](int x, int y, int z) {
    return x == 1 && y == 1 && z == 1 ? 1 : x == 2 && y == 2 && z == 1 ? 2 : 0;
  });
  EXPECT_EQ(cbc3d::MeasureMeshTopology(TissueOnly(r.Before, r.Before.Labels)).Whole.HingedParts, 1);
  ExpectSound(r);
}

TEST(ManifoldRepair, ACheckerboardBecomesManifold)
{
  const Repaired r = Repair(6, [](int x, int y, int z) { return Inside(x, y, z, 1, 5) && (x + y + z) % 2 == 0 ? 1 : 0; });
  EXPECT_GT(r.NonManifoldBefore, 0);
  ExpectSound(r);
}

TEST(ManifoldRepair, ATwoTissueCheckerboardBecomesManifold)
{
  const Repaired r = Repair(6, [](int x, int y, int z) { return Inside(x, y, z, 1, 5) ? 1 + (x + y + z) % 2 : 0; });
  EXPECT_GT(r.NonManifoldBefore, 0);
  ExpectSound(r);
}

TEST(ManifoldRepair, AMeshThatPinchesItselfKeepsOneSideOfThePinch)
{
  // Only two cubes exist, sharing one edge: no tet can join them, so one side must go.
  auto two = [](int x, int y, int z) { return (x == 0 && y == 0 && z == 0) || (x == 1 && y == 1 && z == 0); };
  const Repaired r = Repair(2, [&](int x, int y, int z) { return two(x, y, z) ? 1 : 0; }, two);
  ExpectSound(r);
  const cbc3d::MeshTopology after = cbc3d::MeasureMeshTopology(TissueOnly(r.Before, r.Classes));
  EXPECT_GE(after.Whole.FaceComponents, 1);
}

TEST(ManifoldRepair, ANoisyPatternIsRepairedTheSameWithAnyThreads)
{
  // Three labels and background at random: thousands of defects; the first sweep checks the
  // vertices in parallel, and the repairs must not depend on it.
  std::mt19937 random(11);
  std::vector<std::int32_t> noise(14 * 14 * 14);
  for (auto& label : noise)
    label = static_cast<std::int32_t>(random() % 4);
  const Pattern pattern = [&](int x, int y, int z) { return noise[x + 14 * (y + 14 * z)]; };
  const Repaired serial = Repair(14, pattern, nullptr, 1);
  ASSERT_GT(serial.NonManifoldBefore, 100);
  ExpectSound(serial);
  // Every vertex as a seed: the plain serial sweep, without the checks made beforehand.
  std::vector<std::int32_t> plain = serial.Before.Labels;
  std::vector<cbc3d::PointId> every(serial.Before.Points.size());
  for (std::size_t p = 0; p < every.size(); ++p)
    every[p] = static_cast<cbc3d::PointId>(p);
  const auto across = cbc3d::FaceNeighbours(serial.Before.Tets, serial.Before.Points.size());
  const cbc3d::ClassVotes votes = [&](std::int64_t t, std::int32_t cls) {
    return std::int64_t(serial.Before.Labels[t] == cls ? 6 : 0);
  };
  cbc3d::RepairManifoldLabels(serial.Before.Points, serial.Before.Tets, across, Background, votes, plain, every);
  EXPECT_EQ(plain, serial.Classes);
  for (const int threads : { 2, 4 })
  {
    const Repaired parallel = Repair(14, pattern, nullptr, threads);
    EXPECT_EQ(parallel.Classes, serial.Classes) << threads << " threads";
    EXPECT_EQ(parallel.Result.Repairs, serial.Result.Repairs) << threads << " threads";
    EXPECT_EQ(parallel.Result.Relabelled, serial.Result.Relabelled) << threads << " threads";
  }
}
