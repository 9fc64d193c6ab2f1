#include "cbc3d/deformation/TissueVolumes.h"
#include "cbc3d/deformation/VolumeAims.h"
#include "cbc3d/quality/Quality.h"

#include "TestMeshes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <map>

using cbc3d::testing::KuhnGrid;

namespace
{
// Offsets the goals, starting from the points themselves, `rounds` times (each round a
// first-order step from where the last one ended), with every surface point moving.
std::vector<Eigen::Vector3d> OffsetRounds(const cbc3d::TissueVolumeKeeper& keeper, const cbc3d::TetMesh& mesh, int rounds)
{
  std::vector<Eigen::Vector3d> goals = mesh.Points;
  const std::vector<char> moving(mesh.Points.size(), 1); // interior points have no area: they stay
  for (int round = 0; round < rounds; ++round)
    keeper.OffsetGoals(goals, moving);
  return goals;
}
} // namespace

TEST(TissueVolumes, VolumesFromTheBoundaryAreTheTetsVolumes)
{
  // Two unit cubes per tissue side by side, and a third tissue of one cube above.
  const auto mesh = KuhnGrid(4, 1, 2, [](int, int, int z) { return true; },
    [](int x, int, int z, int) { return z == 1 ? 3 : (x < 2 ? 1 : 2); });
  const cbc3d::TissueVolumeKeeper keeper(mesh, {}, 1.0);
  const auto volumes = keeper.Volumes(mesh.Points);
  EXPECT_NEAR(volumes.at(1), 2.0, 1e-12);
  EXPECT_NEAR(volumes.at(2), 2.0, 1e-12);
  EXPECT_NEAR(volumes.at(3), 4.0, 1e-12);
  // The same as summing the tets, far from the origin too.
  auto far = mesh;
  for (auto& p : far.Points)
    p += Eigen::Vector3d(1e5, -2e5, 3e5);
  const auto byTets = cbc3d::TissueMeshVolumes(far);
  for (const auto& [label, volume] : cbc3d::TissueVolumeKeeper(far, {}, 1.0).Volumes(far.Points))
    EXPECT_NEAR(volume, byTets.at(label), 1e-6);
}

TEST(TissueVolumes, AGrownCubeMovesItsFacesOutwardOnly)
{
  // A 3x3x3 cube of unit cubes that should hold 10% more: its faces move out along their
  // normals, its interior points stay, and the volume reaches the target within 0.1% in a few
  // first-order rounds.
  const auto mesh = KuhnGrid(3, 3, 3, [](int, int, int) { return true; }, [](int, int, int, int) { return 1; });
  const cbc3d::TissueVolumeKeeper keeper(mesh, { { 1, 29.7 } }, 1.0);
  const auto goals = OffsetRounds(keeper, mesh, 4);
  EXPECT_NEAR(keeper.Volumes(goals).at(1), 29.7, 0.03);
  const Eigen::Vector3d centre(1.5, 1.5, 1.5);
  for (std::size_t p = 0; p < mesh.Points.size(); ++p)
  {
    const Eigen::Vector3d& x = mesh.Points[p];
    const bool onSurface = x.minCoeff() == 0.0 || x.maxCoeff() == 3.0;
    if (!onSurface)
      EXPECT_EQ(goals[p], x) << "interior point " << p;
    else
      EXPECT_GT((goals[p] - centre).norm(), (x - centre).norm()) << "surface point " << p;
  }
  // In one round a face's middle point moves straight along the face's normal (later rounds
  // start from a cube whose corners have moved, so its faces are no longer flat).
  const auto middle = cbc3d::PointId(1 + 4 * (1 + 4 * 0)); // (1, 1, 0) on the face z = 0
  const auto first = OffsetRounds(keeper, mesh, 1);
  EXPECT_NEAR((first[middle] - mesh.Points[middle]).head<2>().norm(), 0.0, 1e-12);
  EXPECT_LT(first[middle].z(), 0.0);
}

TEST(TissueVolumes, TwoTissuesTradeVolumeAcrossTheirInterface)
{
  // Tissue 1 should hold 1.2 and tissue 2 0.8 of their one unit cube each. The least
  // area-weighted squares spread each shortfall over a tissue's boundary: the interface moves
  // toward tissue 2, tissue 1's outer faces move out and tissue 2's in.
  const auto mesh = KuhnGrid(2, 1, 1, [](int, int, int) { return true; },
    [](int x, int, int, int) { return x == 0 ? 1 : 2; });
  const cbc3d::TissueVolumeKeeper keeper(mesh, { { 1, 1.2 }, { 2, 0.8 } }, 1.0);
  const auto goals = OffsetRounds(keeper, mesh, 4);
  const auto volumes = keeper.Volumes(goals);
  EXPECT_NEAR(volumes.at(1), 1.2, 1e-3);
  EXPECT_NEAR(volumes.at(2), 0.8, 1e-3);
  for (std::size_t p = 0; p < mesh.Points.size(); ++p)
  {
    const Eigen::Vector3d& x = mesh.Points[p];
    if (x.x() == 1.0)
      EXPECT_GT(goals[p].x(), 1.05) << "interface point " << p;
    else if (x.x() == 0.0)
      EXPECT_LT(goals[p].x(), 0.0) << "tissue 1's outer face";
    else
      EXPECT_LT(goals[p].x(), 2.0) << "tissue 2's outer face";
  }
}

TEST(TissueVolumes, OffsetsAreBoundedAndFreeTissuesAreLeftAlone)
{
  const auto mesh = KuhnGrid(2, 2, 2, [](int, int, int) { return true; }, [](int, int, int, int) { return 1; });
  // A target far beyond reach: one call moves no point farther than the bound.
  const cbc3d::TissueVolumeKeeper bounded(mesh, { { 1, 1000.0 } }, 0.25);
  std::vector<Eigen::Vector3d> goals = mesh.Points;
  EXPECT_NEAR(bounded.OffsetGoals(goals, std::vector<char>(goals.size(), 1)), 0.25, 1e-12);
  for (std::size_t p = 0; p < goals.size(); ++p)
    EXPECT_LE((goals[p] - mesh.Points[p]).norm(), 0.25 + 1e-12);
  // No target: nothing moves.
  const cbc3d::TissueVolumeKeeper free(mesh, { { 7, 3.0 } }, 1.0);
  goals = mesh.Points;
  EXPECT_EQ(free.OffsetGoals(goals, std::vector<char>(goals.size(), 1)), 0.0);
  EXPECT_EQ(goals, mesh.Points);
}

TEST(TissueVolumes, ImageVolumesCountEveryTissueVoxelOnAnyThreads)
{
  // Runs of one label cut at every place: labels change often, and the threads' chunks end
  // inside runs.
  cbc3d::LabelImage image;
  image.Dimensions = { 7, 5, 3 };
  image.Spacing = Eigen::Vector3d(0.5, 2.0, 3.0); // 3 mm^3 a voxel
  image.BackgroundLabels = { 0, 5 };
  const int pattern[] = { 1, 1, 1, 0, 2, 2, 5, 5, 1, 7, 7, 7, 7, 0 };
  std::map<std::int32_t, std::int64_t> expected;
  for (int v = 0; v < 105; ++v)
  {
    const std::int32_t label = pattern[(v * v + 3 * v) % 14];
    image.Labels.push_back(label);
    if (label != 0 && label != 5)
      ++expected[label];
  }
  // From the labels on any threads, then from the index of runs (one step per run).
  for (const int threads : { 1, 2, 3, 8, -1 })
  {
    if (threads < 0)
      cbc3d::IndexLabelRuns(image, 2);
    const std::map<std::int32_t, double> volumes = cbc3d::TissueImageVolumes(image, std::max(threads, 1));
    ASSERT_EQ(volumes.size(), expected.size()) << threads << " threads";
    for (const auto& [label, count] : expected)
      EXPECT_EQ(volumes.at(label), 3.0 * double(count)) << "label " << label << ", " << threads << " threads";
  }
}

TEST(TissueVolumes, AnAimOtherThanTheTargetOffsetsInProportionToFirstOrder)
{
  // A 2 mm cube of one tissue: 8 mm^3 that meets its target, so nothing moves unless it aims
  // elsewhere; the offsets are linear in the shortfall asked for.
  const auto mesh = KuhnGrid(2, 2, 2, [](int, int, int) { return true; }, [](int, int, int, int) { return 1; });
  const cbc3d::TissueVolumeKeeper keeper(mesh, { { 1, 8.0 } }, 1.0);
  const std::vector<char> moving(mesh.Points.size(), 1);
  std::vector<Eigen::Vector3d> met = mesh.Points, once = mesh.Points, twice = mesh.Points;
  EXPECT_NEAR(keeper.OffsetGoals(met, moving), 0.0, 1e-12);
  const double offset = keeper.OffsetGoals(once, moving, { { 1, 8.8 } });
  EXPECT_NEAR(keeper.OffsetGoals(twice, moving, { { 1, 9.6 } }), 2.0 * offset, 1e-12);
  // To first order: the 0.8 mm^3 asked for, give or take the growth of the edges and corners.
  EXPECT_GT(offset, 0.8 / 24.0 * 0.9);
  EXPECT_NEAR(keeper.Volumes(once).at(1), 8.8, 0.05);
}

TEST(VolumeAims, ATissueThatGotPartOfItsShortfallAsksForMoreUntilItIsNear)
{
  const std::map<std::int32_t, double> targets = { { 1, 100.0 }, { 2, 50.0 }, { 3, 0.0 } };
  cbc3d::VolumeAims aims(targets);
  // The first round asks for the targets themselves; a free tissue (no volume above 0) is left out.
  const std::map<std::int32_t, double> start = { { 1, 60.0 }, { 2, 40.0 }, { 3, 5.0 } };
  const auto first = aims.Aims(start);
  EXPECT_EQ(first, (std::map<std::int32_t, double>{ { 1, 100.0 }, { 2, 50.0 } }));
  // Tissue 1 got a quarter of its 40 (asks twice, the most), tissue 2 went the wrong way.
  aims.Observe(start, first, { { 1, 70.0 }, { 2, 38.0 } });
  const auto second = aims.Aims({ { 1, 70.0 }, { 2, 38.0 } });
  EXPECT_DOUBLE_EQ(second.at(1), 70.0 + 2.0 * 30.0);
  EXPECT_DOUBLE_EQ(second.at(2), 50.0);
  // Tissue 1 then got 40 of the 60 it asked for, past its target: 1.5 times its excess next.
  // Tissue 2 got 14 of the 12 it asked for: no gain below 1.
  aims.Observe({ { 1, 70.0 }, { 2, 38.0 } }, second, { { 1, 110.0 }, { 2, 52.0 } });
  const auto third = aims.Aims({ { 1, 110.0 }, { 2, 52.0 } });
  EXPECT_DOUBLE_EQ(third.at(1), 110.0 - 1.5 * 10.0);
  EXPECT_DOUBLE_EQ(third.at(2), 50.0);
  // Within 1% of its target a tissue asks for the plain shortfall, whatever it learnt.
  EXPECT_DOUBLE_EQ(aims.Aims({ { 1, 99.5 } }).at(1), 100.0);
}

TEST(TissueVolumes, AreaSumsAreEachPointsOutwardFaceAreasOnAnyThreads)
{
  // One tissue in a 3 x 2 x 2 block, its points jiggled so that no two faces are alike: one
  // interface (the tissue and the outside), so each moving boundary point has one sum.
  auto mesh = KuhnGrid(3, 2, 2, [](int, int, int) { return true; }, [](int, int, int, int) { return 1; });
  for (std::size_t p = 0; p < mesh.Points.size(); ++p)
    mesh.Points[p] += 0.05 * Eigen::Vector3d(std::sin(1.0 + p), std::cos(2.0 * p), std::sin(3.0 * p));
  const cbc3d::TissueVolumeKeeper keeper(mesh, { { 1, 1.0 } }, 1.0);
  std::vector<char> moving(mesh.Points.size(), 0);
  for (std::size_t p = 0; p < moving.size(); p += 2)
    moving[p] = 1; // every other point
  const cbc3d::TissueVolumeKeeper::AreaSums sums(keeper, moving);
  const auto one = sums.At(mesh.Points, 1), four = sums.At(mesh.Points, 4);
  // Brute force: half the cross product of each boundary face, turned away from its tet.
  std::map<cbc3d::PointId, Eigen::Vector3d> expected;
  for (const cbc3d::MeshFace& face : cbc3d::SurfaceFaces(mesh))
  {
    const auto& x = mesh.Points;
    const auto& [a, b, c] = face.Points;
    Eigen::Vector3d area = 0.5 * (x[b] - x[a]).cross(x[c] - x[a]);
    const auto& tet = mesh.Tets[face.Tets[0]];
    for (const cbc3d::PointId d : tet)
      if (d != a && d != b && d != c && area.dot(x[d] - x[a]) > 0.0)
        area = -area;
    for (const cbc3d::PointId p : face.Points)
      if (moving[p])
        expected.emplace(p, Eigen::Vector3d::Zero()).first->second += area;
  }
  ASSERT_EQ(one.size(), expected.size());
  ASSERT_EQ(four.size(), expected.size());
  auto wanted = expected.begin();
  for (std::size_t i = 0; i < one.size(); ++i, ++wanted)
  {
    EXPECT_EQ(one[i].Point, wanted->first); // ascending points
    EXPECT_LT((one[i].Area - wanted->second).norm(), 1e-12) << "point " << one[i].Point;
    EXPECT_EQ(one[i].Point, four[i].Point);
    EXPECT_EQ(one[i].Area, four[i].Area); // bit for bit on any threads
  }
}
