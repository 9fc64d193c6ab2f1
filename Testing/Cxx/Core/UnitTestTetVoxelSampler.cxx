#include "cbc3d/TetVoxelSampler.h"

#include <gtest/gtest.h>

#include "TestImages.h"

TEST(TetVoxelSampler, CountsVoxelCentresInsideAndOnTheFaces)
{
  const cbc3d::LabelImage image = Cube(6, 7);
  // Corner tet of side 4: the grid points with i, j, k >= 0 and i + j + k <= 4, C(7,3) = 35.
  const std::array<Eigen::Vector3d, 4> corners = { Eigen::Vector3d(0, 0, 0),
    Eigen::Vector3d(4, 0, 0), Eigen::Vector3d(0, 4, 0), Eigen::Vector3d(0, 0, 4) };
  cbc3d::LabelCounts counts;
  cbc3d::SampleTetLabels(image, corners, counts);
  EXPECT_EQ(counts.Total(), 35);
  std::int32_t label = 0;
  ASSERT_TRUE(counts.MajorityTissue(image, label));
  EXPECT_EQ(label, 7);
}

TEST(TetVoxelSampler, UpsamplesATetThatHoldsNoVoxelCentre)
{
  cbc3d::LabelImage image = Cube(4, 0);
  image.Labels[image.VoxelIndex(1, 2, 1)] = 3;
  // A tet inside voxel (1,2,1) (centre (1,2,1), extent +-0.5) that misses its centre.
  const std::array<Eigen::Vector3d, 4> corners = { Eigen::Vector3d(0.6, 1.6, 0.6),
    Eigen::Vector3d(0.95, 1.6, 0.6), Eigen::Vector3d(0.6, 1.95, 0.6),
    Eigen::Vector3d(0.6, 1.6, 0.95) };
  cbc3d::LabelCounts counts;
  cbc3d::SampleTetLabels(image, corners, counts);
  ASSERT_GT(counts.Total(), 0);
  EXPECT_EQ(counts.TissueTotal(image), counts.Total());
  std::int32_t label = 0;
  ASSERT_TRUE(counts.MajorityTissue(image, label));
  EXPECT_EQ(label, 3);
}

TEST(TetVoxelSampler, MajorityTieGoesToTheSmallerTissueLabel)
{
  cbc3d::LabelImage image = Cube(3, 0);
  cbc3d::LabelCounts counts;
  counts.Add(9);
  counts.Add(4);
  counts.Add(0);
  counts.Add(0);
  counts.Add(0);
  std::int32_t label = -1;
  ASSERT_TRUE(counts.MajorityTissue(image, label)); // background 0 never wins
  EXPECT_EQ(label, 4);
  EXPECT_EQ(counts.TissueTotal(image), 2);
}
