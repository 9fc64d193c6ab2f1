// Refinement's size controls: edge limits per tissue and for all, the edge floor, fidelity per
// tissue, and one clear error for each bad value.
#include "cbc3d/base/TetTopology.h"
#include "cbc3d/deformation/Deformation.h"
#include "cbc3d/lattice/BCCLattice.h"
#include "cbc3d/refinement/Refinement.h"

#include "TestImages.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace
{
// Two boxes side by side in a 32^3 image of 1 mm voxels: label 1 at x in [4, 16),
// label 2 at x in [16, 28), both at y, z in [4, 16).
cbc3d::LabelImage TwoBoxes()
{
  cbc3d::LabelImage image = Cube(32, 0);
  for (int k = 4; k < 16; ++k)
    for (int j = 4; j < 16; ++j)
      for (int i = 4; i < 28; ++i)
        image.Labels[image.VoxelIndex(i, j, k)] = i < 16 ? 1 : 2;
  return image;
}

// Per label: the longest and the shortest edge of its tets.
struct EdgeRange
{
  double Longest = 0.0;
  double Shortest = std::numeric_limits<double>::infinity();
};

std::map<std::int32_t, EdgeRange> EdgesByLabel(const cbc3d::TetMesh& mesh)
{
  std::map<std::int32_t, EdgeRange> ranges;
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    EdgeRange& range = ranges[mesh.Labels[t]];
    for (const auto& edge : cbc3d::TetEdges)
    {
      const double length = (mesh.Points[mesh.Tets[t][edge[0]]] - mesh.Points[mesh.Tets[t][edge[1]]]).norm();
      range.Longest = std::max(range.Longest, length);
      range.Shortest = std::min(range.Shortest, length);
    }
  }
  return ranges;
}

cbc3d::RefinementParams Coarse()
{
  cbc3d::RefinementParams params;
  params.Fidelity = 0.0; // sizes alone drive refinement
  params.BoundaryDistance = -1.0;
  return params;
}
} // namespace

TEST(SizeControls, WithoutALimitTheLatticeEdgesStay)
{
  // The control case: the limits below must be what shortens the edges.
  const cbc3d::LabelImage image = TwoBoxes();
  cbc3d::TetMesh mesh;
  cbc3d::RefinementResult result;
  ASSERT_TRUE(cbc3d::RefineMesh(image, Lattice(image, 8.0), Coarse(), mesh, result).IsOk());
  const auto edges = EdgesByLabel(mesh);
  EXPECT_NEAR(edges.at(1).Longest, 8.0, 1e-9); // a BCC tet's cube edge
  EXPECT_NEAR(edges.at(2).Longest, 8.0, 1e-9);
}

TEST(SizeControls, EveryTetOfATissueKeepsItsEdgeLimit)
{
  const cbc3d::LabelImage image = TwoBoxes();
  cbc3d::RefinementParams params = Coarse();
  params.MaximumEdge.All = 4.0;
  params.MaximumEdge.ByTissue[1] = 2.0;
  cbc3d::TetMesh mesh;
  cbc3d::RefinementResult result;
  ASSERT_TRUE(cbc3d::RefineMesh(image, Lattice(image, 8.0), params, mesh, result).IsOk());
  EXPECT_TRUE(cbc3d::ValidateTetMesh(mesh).IsOk());
  const auto edges = EdgesByLabel(mesh);
  EXPECT_LE(edges.at(1).Longest, 2.0 + 1e-9);
  EXPECT_LE(edges.at(2).Longest, 4.0 + 1e-9);
  // Tissue 2 is graded, not refined to tissue 1's size throughout.
  EXPECT_GT(edges.at(2).Longest, 2.0 + 1e-9);
  EXPECT_EQ(result.OverlongTets, 0u);
}

TEST(SizeControls, TheFloorStopsSplitsAndTheReportSaysSo)
{
  // A 3 mm floor leaves the 8 mm lattice's tets (shortest edge 6.93 mm) one split at most: an
  // edge limit of 3.5 mm cannot be met everywhere, and the result counts the tets left over.
  const cbc3d::LabelImage image = TwoBoxes();
  cbc3d::RefinementParams params = Coarse();
  params.MinimumEdgeLength = 3.0;
  params.MaximumEdge.All = 3.5;
  cbc3d::TetMesh mesh;
  cbc3d::RefinementResult result;
  ASSERT_TRUE(cbc3d::RefineMesh(image, Lattice(image, 8.0), params, mesh, result).IsOk());
  for (const auto& [label, range] : EdgesByLabel(mesh))
    EXPECT_GE(range.Shortest, 3.0 * (1.0 - 1e-9)) << "label " << label;
  EXPECT_GT(result.OverlongTets, 0u);
}

TEST(SizeControls, FidelityPerTissueReplacesTheCommonTarget)
{
  // A ball of label 1 and one of label 2: with the common target 0, only tissue 2 (0.95) is
  // refined for fidelity.
  cbc3d::LabelImage image = Cube(32, 0);
  PaintBall(image, Eigen::Vector3d(9, 16, 16), 6.0, 1);
  PaintBall(image, Eigen::Vector3d(23, 16, 16), 6.0, 2);
  cbc3d::RefinementParams params = Coarse();
  params.FidelityByTissue[2] = 0.95;
  params.MinimumEdgeLength = 0.5;
  cbc3d::TetMesh mesh;
  cbc3d::RefinementResult result;
  ASSERT_TRUE(cbc3d::RefineMesh(image, Lattice(image, 8.0), params, mesh, result).IsOk());
  ASSERT_EQ(result.Tissues.size(), 2u);
  EXPECT_GE(result.Tissues[1].F1, 0.95);
  EXPECT_GE(result.Tissues[1].F2, 0.95);
  EXPECT_LT(std::min(result.Tissues[0].F1, result.Tissues[0].F2), 0.95);
  const auto edges = EdgesByLabel(mesh);
  EXPECT_LT(edges.at(2).Shortest, edges.at(1).Shortest);
}

TEST(SizeControls, BadValuesGetOneClearError)
{
  const cbc3d::LabelImage image = TwoBoxes();
  const cbc3d::TetMesh lattice = Lattice(image, 8.0);
  const auto error = [&](const cbc3d::RefinementParams& params) {
    cbc3d::TetMesh mesh;
    cbc3d::RefinementResult result;
    const cbc3d::Status status = cbc3d::RefineMesh(image, lattice, params, mesh, result);
    EXPECT_FALSE(status.IsOk());
    return status.GetMessage();
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  cbc3d::RefinementParams params = Coarse();
  params.MaximumEdge.All = -1.0;
  EXPECT_NE(error(params).find("maximum edge length"), std::string::npos);
  params.MaximumEdge.All = nan;
  EXPECT_NE(error(params).find("maximum edge length"), std::string::npos);
  params = Coarse();
  params.MaximumEdge.ByTissue[1] = 0.0;
  EXPECT_NE(error(params).find("tissue 1"), std::string::npos);
  params = Coarse();
  params.MaximumEdge.ByTissue[7] = 2.0;
  EXPECT_NE(error(params).find("no voxel of tissue 7"), std::string::npos);
  params = Coarse();
  params.MaximumEdge.ByTissue[0] = 2.0;
  EXPECT_NE(error(params).find("background"), std::string::npos);
  params = Coarse();
  params.FidelityByTissue[2] = nan;
  EXPECT_NE(error(params).find("fidelity of tissue 2"), std::string::npos);
  params = Coarse();
  params.MinimumEdgeLength = 1.0;
  params.MaximumEdge.All = 0.5; // below the floor the user gave
  EXPECT_NE(error(params).find("below the minimum edge length"), std::string::npos);
}

TEST(SizeControls, DeformationStretchesNoEdgePastItsLimit)
{
  // A ball's lattice tets (longest edge 4 mm) deformed onto its sphere: without a limit some
  // edge grows past 4 mm, with the limit none does.
  const cbc3d::LabelImage image = BallImage(24, 8.0);
  cbc3d::TetMesh start;
  cbc3d::RefinementResult refined;
  ASSERT_TRUE(cbc3d::RefineMesh(image, Lattice(image, 4.0), Coarse(), start, refined).IsOk());
  ASSERT_LE(EdgesByLabel(start).at(1).Longest, 4.0 + 1e-9);
  const auto deform = [&](double limit) {
    cbc3d::DeformationParams params;
    params.MaximumEdge.All = limit;
    cbc3d::TetMesh moved;
    cbc3d::DeformationResult result;
    EXPECT_TRUE(cbc3d::DeformMesh(image, start, params, moved, result).IsOk());
    EXPECT_GT(result.Iterations, 0);
    return EdgesByLabel(moved).at(1).Longest;
  };
  EXPECT_GT(deform(0.0), 4.0 + 1e-6);
  EXPECT_LE(deform(4.0), 4.0 + 1e-9);
}

TEST(SizeControls, ATetBudgetEndsWithinNinetyPercentAndTheBudget)
{
  // Nested balls asked for fidelity 0.99 make more tets than the budget without it.
  cbc3d::LabelImage image = Cube(40, 0);
  PaintBall(image, Eigen::Vector3d(19.5, 19.5, 19.5), 15.0, 1);
  PaintBall(image, Eigen::Vector3d(17.0, 19.5, 19.5), 8.0, 2);
  PaintBall(image, Eigen::Vector3d(24.0, 21.0, 19.5), 4.0, 3);
  const cbc3d::TetMesh lattice = Lattice(image, 8.0);
  cbc3d::RefinementParams params;
  params.Fidelity = 0.99;
  cbc3d::TetMesh free, budgeted;
  cbc3d::RefinementResult freeResult, result;
  ASSERT_TRUE(cbc3d::RefineMesh(image, lattice, params, free, freeResult).IsOk());
  const std::int64_t budget = 4000;
  ASSERT_GT(static_cast<std::int64_t>(free.Tets.size()), budget);
  params.MaximumTets = budget;
  ASSERT_TRUE(cbc3d::RefineMesh(image, lattice, params, budgeted, result).IsOk());
  EXPECT_LE(static_cast<std::int64_t>(budgeted.Tets.size()), budget);
  EXPECT_GE(static_cast<std::int64_t>(budgeted.Tets.size()), budget * 9 / 10);
  EXPECT_EQ(result.StopReason, "the tet budget is spent");
  EXPECT_TRUE(cbc3d::ValidateTetMesh(budgeted).IsOk());
  params.MaximumTets = -1;
  EXPECT_FALSE(cbc3d::RefineMesh(image, lattice, params, budgeted, result).IsOk());
}

TEST(SizeControls, ABudgetCoarsensTheAutomaticLatticeOnly)
{
  // 1000 mm^3 of tissue: 12 tets per cube, a quarter of a 48-tet budget, is a 10 mm cube.
  const cbc3d::LabelImage image = Cube(10, 1);
  EXPECT_NEAR(cbc3d::BudgetLatticeEdgeLength(image, 48), 10.0, 1e-9);
  cbc3d::LatticeParams params;
  EXPECT_NEAR(cbc3d::LatticeEdgeLengthFor(image, params), 8.0, 1e-12); // the automatic 8 voxels
  params.MaximumTets = 48;
  EXPECT_NEAR(cbc3d::LatticeEdgeLengthFor(image, params), 10.0, 1e-9);
  params.MaximumTets = 1000000; // a generous budget keeps the automatic size
  EXPECT_NEAR(cbc3d::LatticeEdgeLengthFor(image, params), 8.0, 1e-12);
  params.EdgeLength = 3.0; // a size the user gave is kept
  params.MaximumTets = 48;
  EXPECT_NEAR(cbc3d::LatticeEdgeLengthFor(image, params), 3.0, 1e-12);
}
