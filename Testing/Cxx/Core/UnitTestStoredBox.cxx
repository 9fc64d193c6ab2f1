// A label image that stores only the box of its voxels that are not the first background label
// (and one voxel around it) must give every stage the same answers as the whole image: the
// stages' voxel indices then count within the box, so they are compared by voxel coordinates.
#include "cbc3d/base/LabelImage.h"
#include "cbc3d/deformation/BoundaryTargets.h"
#include "cbc3d/deformation/Deformation.h"
#include "cbc3d/quality/ImageTopology.h"
#include "cbc3d/refinement/Refinement.h"
#include "cbc3d/sampling/SurfacePoints.h"
#include "cbc3d/sampling/TetVoxelSampler.h"
#include "cbc3d/sampling/TissueComponents.h"

#include <gtest/gtest.h>

#include "TestImages.h"

#include <algorithm>

namespace
{
// Two tissues and a cavity, well inside a 30^3 image of background 0 (the padding).
cbc3d::LabelImage PaddedImage()
{
  cbc3d::LabelImage image = Cube(30, 0);
  PaintBall(image, Eigen::Vector3d(9, 10, 8), 5.0, 3);
  PaintBall(image, Eigen::Vector3d(13, 10, 9), 3.5, 5);
  PaintBall(image, Eigen::Vector3d(8, 10, 8), 1.5, 0); // a cavity of the background
  image.Spacing = Eigen::Vector3d(1.0, 0.9, 1.2);
  image.Origin = Eigen::Vector3d(-3.0, 2.0, 1.0);
  return image;
}

// The same image storing only its box of voxels other than the first background label, and
// one voxel around it (what the VTK conversion stores).
cbc3d::LabelImage Stored(const cbc3d::LabelImage& whole)
{
  const auto& d = whole.Dimensions;
  std::array<int, 3> lower = d, upper = { -1, -1, -1 };
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i)
        if (whole.LabelAt(i, j, k) != whole.BackgroundLabels.front())
          for (int a = 0; a < 3; ++a)
          {
            lower[a] = std::min(lower[a], std::array<int, 3>{ i, j, k }[a]);
            upper[a] = std::max(upper[a], std::array<int, 3>{ i, j, k }[a]);
          }
  cbc3d::LabelImage box = whole;
  for (int a = 0; a < 3; ++a)
  {
    box.StoredLower[a] = std::max(lower[a] - 1, 0);
    box.StoredSize[a] = std::min(upper[a] + 1, d[a] - 1) - box.StoredLower[a] + 1;
  }
  box.Labels.clear();
  for (int k = box.StoredLower[2]; k < box.StoredLower[2] + box.StoredSize[2]; ++k)
    for (int j = box.StoredLower[1]; j < box.StoredLower[1] + box.StoredSize[1]; ++j)
      for (int i = box.StoredLower[0]; i < box.StoredLower[0] + box.StoredSize[0]; ++i)
        box.Labels.push_back(whole.LabelAt(i, j, k));
  return box;
}

// A voxel index of `from` as the index of the same voxel in `to`.
std::int64_t Same(const cbc3d::LabelImage& from, const cbc3d::LabelImage& to, std::int64_t voxel)
{
  const auto at = from.VoxelCoordinates(voxel);
  return to.VoxelIndex(at[0], at[1], at[2]);
}

void ExpectSameMesh(const cbc3d::TetMesh& a, const cbc3d::TetMesh& b)
{
  ASSERT_EQ(a.Tets.size(), b.Tets.size());
  EXPECT_EQ(a.Tets, b.Tets);
  EXPECT_EQ(a.Labels, b.Labels);
  ASSERT_EQ(a.Points.size(), b.Points.size());
  for (std::size_t p = 0; p < a.Points.size(); ++p)
    EXPECT_EQ(a.Points[p], b.Points[p]) << "point " << p; // bit for bit
}
} // namespace

TEST(StoredBox, StoresLessAndReadsTheSameLabels)
{
  const cbc3d::LabelImage whole = PaddedImage();
  const cbc3d::LabelImage box = Stored(whole);
  ASSERT_TRUE(cbc3d::ValidateLabelImage(box).IsOk());
  EXPECT_LT(box.Labels.size() * 8, whole.Labels.size());
  for (int k = 0; k < 30; ++k)
    for (int j = 0; j < 30; ++j)
      for (int i = 0; i < 30; ++i)
        ASSERT_EQ(box.LabelOf(i, j, k), whole.LabelAt(i, j, k));
  EXPECT_EQ(box.TissueLabels(), whole.TissueLabels());
  std::array<int, 3> lowerA, upperA, lowerB, upperB;
  ASSERT_TRUE(cbc3d::TissueIndexBounds(whole, lowerA, upperA));
  ASSERT_TRUE(cbc3d::TissueIndexBounds(box, lowerB, upperB));
  EXPECT_EQ(lowerA, lowerB);
  EXPECT_EQ(upperA, upperB);
  for (std::int64_t v = 0; v < std::int64_t(box.Labels.size()); v += 7)
    EXPECT_EQ(box.VoxelCentre(v), whole.VoxelCentre(Same(box, whole, v)));
  cbc3d::LabelImage wrong = box;
  wrong.StoredLower[0] = 29;
  EXPECT_FALSE(cbc3d::ValidateLabelImage(wrong).IsOk());
  wrong = box;
  wrong.BackgroundLabels.clear();
  EXPECT_FALSE(cbc3d::ValidateLabelImage(wrong).IsOk());
}

TEST(StoredBox, ComponentsBoundaryVoxelsTargetsAndTopologyAgree)
{
  const cbc3d::LabelImage whole = PaddedImage();
  const cbc3d::LabelImage box = Stored(whole);
  const cbc3d::TissueComponents a = cbc3d::FindTissueComponents(whole), b = cbc3d::FindTissueComponents(box);
  EXPECT_EQ(a.Label, b.Label);
  EXPECT_EQ(a.Size, b.Size);
  // The runs list every tissue voxel (and no other), ascending, in the whole image and the box.
  std::vector<std::int64_t> aVoxels, bVoxels, tissue;
  std::vector<std::int32_t> aComponents, bComponents;
  a.ForEachVoxel([&](std::int64_t v, std::int32_t c) { aVoxels.push_back(v); aComponents.push_back(c); });
  b.ForEachVoxel([&](std::int64_t v, std::int32_t c) { bVoxels.push_back(v); bComponents.push_back(c); });
  for (std::int64_t v = 0; v < std::int64_t(whole.Labels.size()); ++v)
    if (whole.IsTissue(whole.Labels[v]))
      tissue.push_back(v);
  EXPECT_EQ(aVoxels, tissue);
  ASSERT_EQ(aVoxels.size(), bVoxels.size());
  for (std::size_t n = 0; n < aVoxels.size(); ++n)
  {
    ASSERT_EQ(Same(whole, box, aVoxels[n]), bVoxels[n]);
    EXPECT_EQ(aComponents[n], bComponents[n]);
    EXPECT_EQ(a.ComponentOf(aVoxels[n]), aComponents[n]);
    EXPECT_EQ(b.ComponentOf(bVoxels[n]), bComponents[n]);
  }
  const cbc3d::BackgroundComponents ga = cbc3d::FindBackgroundComponents(whole),
                                    gb = cbc3d::FindBackgroundComponents(box);
  EXPECT_EQ(ga.Size, gb.Size);
  EXPECT_EQ(ga.TouchesBorder, gb.TouchesBorder);
  EXPECT_EQ(std::count(gb.TouchesBorder.begin(), gb.TouchesBorder.end(), 0), 1); // the cavity
  for (std::int64_t v = 0; v < std::int64_t(box.Labels.size()); ++v)
    ASSERT_EQ(gb.ComponentOf(v), ga.ComponentOf(Same(box, whole, v)));

  const auto boundaryA = cbc3d::TissueBoundaryVoxels(whole, 2), boundaryB = cbc3d::TissueBoundaryVoxels(box, 2);
  ASSERT_EQ(boundaryA.size(), boundaryB.size());
  for (const auto& [label, voxels] : boundaryA)
  {
    ASSERT_EQ(voxels.size(), boundaryB.at(label).size());
    for (std::size_t n = 0; n < voxels.size(); ++n)
      EXPECT_EQ(Same(whole, box, voxels[n]), boundaryB.at(label)[n]);
  }
  for (const auto placement : { cbc3d::TargetPlacement::VoxelCentre, cbc3d::TargetPlacement::VoxelFace })
  {
    const auto ta = cbc3d::FindBoundaryTargets(whole, cbc3d::TargetPattern::Edge, placement);
    const auto tb = cbc3d::FindBoundaryTargets(box, cbc3d::TargetPattern::Edge, placement);
    ASSERT_EQ(ta.size(), tb.size());
    for (std::size_t n = 0; n < ta.size(); ++n)
    {
      EXPECT_EQ(ta[n].Position, tb[n].Position);
      EXPECT_EQ(ta[n].Labels, tb[n].Labels);
    }
  }
  const cbc3d::ImageTopology topologyA = cbc3d::MeasureImageTopology(whole, 2);
  const cbc3d::ImageTopology topologyB = cbc3d::MeasureImageTopology(box, 2);
  EXPECT_EQ(topologyA.WholeSurfaceEuler, topologyB.WholeSurfaceEuler);
  EXPECT_EQ(topologyA.TissueSurfaceEuler, topologyB.TissueSurfaceEuler);
}

TEST(StoredBox, SamplesCountBeyondTheBoxAsBeyondTheImage)
{
  const cbc3d::LabelImage whole = PaddedImage();
  const cbc3d::LabelImage box = Stored(whole);
  // Lattices of large and small tets, reaching far beyond the box and the image.
  for (const double edge : { 30.0, 6.0, 0.7 })
  {
    const cbc3d::TetMesh lattice = Lattice(whole, edge);
    std::vector<std::int32_t> ownerA(whole.Labels.size(), -1), ownerB(box.Labels.size(), -1);
    for (std::size_t t = 0; t < lattice.Tets.size(); ++t)
    {
      std::array<Eigen::Vector3d, 4> corners;
      for (int v = 0; v < 4; ++v)
        corners[v] = lattice.Points[lattice.Tets[t][v]];
      cbc3d::LabelCounts ca, cb;
      EXPECT_EQ(cbc3d::SampleTetLabels(whole, corners, ca, std::int32_t(t), ownerA.data()),
        cbc3d::SampleTetLabels(box, corners, cb, std::int32_t(t), ownerB.data()));
      ASSERT_EQ(ca.Counts, cb.Counts) << "tet " << t << " of the " << edge << " mm lattice"; // in order
    }
    for (std::int64_t v = 0; v < std::int64_t(box.Labels.size()); ++v)
      ASSERT_EQ(ownerB[v], ownerA[Same(box, whole, v)]);
  }
}

TEST(StoredBox, RefinementAndDeformationMakeTheSameMesh)
{
  const cbc3d::LabelImage whole = PaddedImage();
  const cbc3d::LabelImage box = Stored(whole);
  const cbc3d::TetMesh lattice = Lattice(whole, 4.0);
  cbc3d::RefinementParams params;
  params.NumberOfThreads = 2;
  cbc3d::TetMesh refinedA, refinedB;
  cbc3d::RefinementResult resultA, resultB;
  ASSERT_TRUE(cbc3d::RefineMesh(whole, lattice, params, refinedA, resultA).IsOk());
  ASSERT_TRUE(cbc3d::RefineMesh(box, lattice, params, refinedB, resultB).IsOk());
  ExpectSameMesh(refinedA, refinedB);
  cbc3d::DeformationParams deformation;
  deformation.NumberOfThreads = 2;
  cbc3d::TetMesh deformedA, deformedB;
  cbc3d::DeformationResult movedA, movedB;
  ASSERT_TRUE(cbc3d::DeformMesh(whole, refinedA, deformation, deformedA, movedA).IsOk());
  ASSERT_TRUE(cbc3d::DeformMesh(box, refinedB, deformation, deformedB, movedB).IsOk());
  ExpectSameMesh(deformedA, deformedB);
}
