#include "cbc3d/sampling/TetVoxelSampler.h"

#include <Eigen/LU>

#include <algorithm>
#include <random>
#include <gtest/gtest.h>

#include "TestImages.h"

TEST(TetVoxelSampler, TetsOfACubeShareOutItsVoxelCentresOnce)
{
  // The six tets around the diagonal of the cube [0,4]^3 (corner c has bits x=1, y=2, z=4).
  // Points on shared faces go to exactly one tet; on the cube's own faces the tie-break
  // direction (all components positive) keeps the lower faces and leaves the upper ones to the
  // next cube: the tets own exactly the 4 x 4 x 4 centres with i, j, k in [0, 4).
  const cbc3d::LabelImage image = Cube(6, 7);
  auto corner = [](int c) { return Eigen::Vector3d(c & 1 ? 4 : 0, c & 2 ? 4 : 0, c & 4 ? 4 : 0); };
  const int tets[6][4] = { { 0, 1, 3, 7 }, { 0, 3, 2, 7 }, { 0, 2, 6, 7 }, { 0, 6, 4, 7 },
    { 0, 4, 5, 7 }, { 0, 5, 1, 7 } };
  std::vector<std::int32_t> owner(image.Labels.size(), -1);
  std::int64_t total = 0;
  for (int t = 0; t < 6; ++t)
  {
    cbc3d::LabelCounts counts;
    cbc3d::SampleTetLabels(image, { corner(tets[t][0]), corner(tets[t][1]), corner(tets[t][2]),
      corner(tets[t][3]) }, counts, t, owner.data());
    total += counts.Total();
    std::int32_t label = 0;
    ASSERT_TRUE(counts.MajorityTissue(image, label));
    EXPECT_EQ(label, 7);
  }
  EXPECT_EQ(total, 64 * cbc3d::VoxelWeight);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i)
        EXPECT_EQ(owner[image.VoxelIndex(i, j, k)] >= 0, i < 4 && j < 4 && k < 4) << i << j << k;
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
  EXPECT_EQ(counts.TissueTotal(image), 2 * cbc3d::VoxelWeight);
  std::int32_t any = -1;
  ASSERT_TRUE(counts.Majority(image, any)); // background 0 has the most weight
  EXPECT_EQ(any, 0);
}

TEST(TetVoxelSampler, MajorityTieGoesToTissueOverBackground)
{
  const cbc3d::LabelImage image = Cube(3, 0);
  cbc3d::LabelCounts counts;
  counts.Add(0);
  counts.Add(7);
  counts.Add(5);
  counts.Add(0);
  counts.Add(7);
  counts.Add(5);
  std::int32_t label = -1;
  ASSERT_TRUE(counts.Majority(image, label)); // 0, 5 and 7 tie: tissue first, then the smaller
  EXPECT_EQ(label, 5);
  counts.Add(0);
  ASSERT_TRUE(counts.Majority(image, label)); // a strict majority of background still wins
  EXPECT_EQ(label, 0);
}

TEST(TetVoxelSampler, BeyondTheImageCountsAsBackground)
{
  // An image of tissue 7 (voxel centres 0..7, so its box ends at 7.5) and a tet that reaches
  // past x = 7.5: its points inside the image count as tissue, those beyond as background 0.
  // The answer is counted here by brute force (no lattice point lies on the tet's faces).
  const cbc3d::LabelImage image = Cube(8, 7);
  const std::array<Eigen::Vector3d, 4> corners = { Eigen::Vector3d(4.1, 1.05, 1.1),
    Eigen::Vector3d(12.1, 1.05, 1.1), Eigen::Vector3d(4.1, 7.05, 1.1), Eigen::Vector3d(4.1, 1.05, 7.1) };
  Eigen::Matrix3d edges;
  edges << corners[1] - corners[0], corners[2] - corners[0], corners[3] - corners[0];
  const Eigen::Matrix3d toBarycentric = edges.inverse();
  std::int64_t inside = 0, beyond = 0;
  for (int k = 0; k < 16; ++k)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i)
      {
        const Eigen::Vector3d b = toBarycentric * (Eigen::Vector3d(i, j, k) - corners[0]);
        if (b.minCoeff() > 0.0 && b.sum() < 1.0)
          ++(i <= 7 ? inside : beyond);
      }
  ASSERT_GT(inside, 0);
  ASSERT_GT(beyond, 0);
  cbc3d::LabelCounts counts;
  EXPECT_EQ(cbc3d::SampleTetLabels(image, corners, counts), 1);
  EXPECT_EQ(counts.Of(7), inside * cbc3d::VoxelWeight);
  EXPECT_EQ(counts.Of(0), beyond * cbc3d::VoxelWeight);

  // A tet wholly beyond the image holds only background.
  const Eigen::Vector3d away(20.0, 0.0, 0.0);
  EXPECT_EQ(cbc3d::SampleTetLabels(image, { corners[0] + away, corners[1] + away, corners[2] + away, corners[3] + away }, counts), 1);
  std::int32_t label = -1;
  EXPECT_TRUE(counts.Majority(image, label));
  EXPECT_EQ(label, 0);
  EXPECT_EQ(counts.TissueTotal(image), 0);
}

TEST(TetVoxelSampler, TetsFarLargerThanTheImageCountEverySampleOnce)
{
  // The six tets of the cube [-20, 24)^3 around a 6^3 image of tissue 7: rows beyond the image
  // on every side, and rows through it, are counted per run. As in the cube above, the tets
  // share out the cube's 44^3 lattice points once; the 216 in the image are tissue, the rest
  // background.
  const cbc3d::LabelImage image = Cube(6, 7);
  auto corner = [](int c) {
    return Eigen::Vector3d(c & 1 ? 24 : -20, c & 2 ? 24 : -20, c & 4 ? 24 : -20);
  };
  const int tets[6][4] = { { 0, 1, 3, 7 }, { 0, 3, 2, 7 }, { 0, 2, 6, 7 }, { 0, 6, 4, 7 },
    { 0, 4, 5, 7 }, { 0, 5, 1, 7 } };
  std::vector<std::int32_t> owner(image.Labels.size(), -1);
  std::int64_t tissue = 0, background = 0;
  for (int t = 0; t < 6; ++t)
  {
    cbc3d::LabelCounts counts;
    EXPECT_EQ(cbc3d::SampleTetLabels(image, { corner(tets[t][0]), corner(tets[t][1]),
      corner(tets[t][2]), corner(tets[t][3]) }, counts, t, owner.data()), 1);
    tissue += counts.Of(7);
    background += counts.Of(0);
  }
  EXPECT_EQ(tissue, 216 * cbc3d::VoxelWeight);
  EXPECT_EQ(background, (44 * 44 * 44 - 216) * cbc3d::VoxelWeight);
  EXPECT_EQ(std::count(owner.begin(), owner.end(), -1), 0); // every voxel has its one tet

  // The same cube moved wholly to one side of the image along x (its rows through the image's
  // y and z range end before the image, or start after it): all background.
  for (const double shift : { -30.0, 30.0 })
  {
    std::int64_t total = 0;
    for (int t = 0; t < 6; ++t)
    {
      cbc3d::LabelCounts counts;
      const Eigen::Vector3d moved(shift, 0.0, 0.0);
      cbc3d::SampleTetLabels(image, { corner(tets[t][0]) + moved, corner(tets[t][1]) + moved,
        corner(tets[t][2]) + moved, corner(tets[t][3]) + moved }, counts);
      EXPECT_EQ(counts.TissueTotal(image), 0);
      total += counts.Of(0);
    }
    EXPECT_EQ(total, 44 * 44 * 44 * cbc3d::VoxelWeight) << shift;
  }
}

namespace
{
// Tets with random corners, some reaching beyond the image: each must count the voxel centres
// (the integer points) strictly inside it, by label (0-3), those beyond the stored box as
// background, as testing every point of its box would. Random corners put no point on a
// face, so "inside" needs no tie-break here. Returns the tets checked.
int CheckRandomTets(const cbc3d::LabelImage& image, std::mt19937& random)
{
  std::uniform_real_distribution<double> coordinate(-3.0, 23.0), offset(-4.0, 4.0);
  int sampled = 0;
  for (int t = 0; t < 300; ++t)
  {
    std::array<Eigen::Vector3d, 4> corners;
    corners[0] = Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
    const double size = t % 3 == 0 ? 3.0 : 1.0; // small tets, and some of a few voxels across
    for (int v = 1; v < 4; ++v)
      corners[v] = corners[0] + size * Eigen::Vector3d(offset(random), offset(random), offset(random));
    Eigen::Matrix3d edges;
    edges << corners[1] - corners[0], corners[2] - corners[0], corners[3] - corners[0];
    if (std::abs(edges.determinant()) < 1e-3)
      continue;
    const Eigen::Matrix3d toBarycentric = edges.inverse();
    std::array<std::int64_t, 4> expected = { 0, 0, 0, 0 };
    Eigen::Vector3d lower = corners[0], upper = corners[0];
    for (const auto& c : corners)
    {
      lower = lower.cwiseMin(c);
      upper = upper.cwiseMax(c);
    }
    for (int k = int(std::ceil(lower[2])); k <= int(std::floor(upper[2])); ++k)
      for (int j = int(std::ceil(lower[1])); j <= int(std::floor(upper[1])); ++j)
        for (int i = int(std::ceil(lower[0])); i <= int(std::floor(upper[0])); ++i)
        {
          const Eigen::Vector3d b = toBarycentric * (Eigen::Vector3d(i, j, k) - corners[0]);
          if (b.minCoeff() > 0.0 && b.sum() < 1.0)
            ++expected[image.IsStored(i, j, k) ? image.LabelAt(i, j, k) : 0];
        }
    if (expected[0] + expected[1] + expected[2] + expected[3] == 0)
      continue; // such a tet is sampled finer (UpsamplesATetThatHoldsNoVoxelCentre)
    cbc3d::LabelCounts counts;
    EXPECT_EQ(cbc3d::SampleTetLabels(image, corners, counts), 1) << "tet " << t;
    for (int label = 0; label < 4; ++label)
      EXPECT_EQ(counts.Of(label), expected[label] * cbc3d::VoxelWeight) << "tet " << t << " label " << label;
    ++sampled;
  }
  return sampled;
}
} // namespace

TEST(TetVoxelSampler, RandomTetsCountTheVoxelCentresInsideThem)
{
  // A 20^3 image of random labels 0-3, each voxel drawn anew, or kept from the one before
  // along x four times in five (runs, as in label maps); the whole image stored, or a box; the
  // rows' runs indexed or not (without the index, LabelImage::ForEachRun reads the labels).
  std::mt19937 random(17);
  for (const bool runs : { false, true })
    for (const bool box : { false, true })
      for (const bool indexed : { false, true })
      {
        cbc3d::LabelImage image;
        image.Dimensions = { 20, 20, 20 };
        if (box)
        {
          image.StoredLower = { 2, 3, 1 };
          image.StoredSize = { 15, 14, 16 };
        }
        image.Labels.resize(std::size_t(image.StoredDimensions()[0]) * image.StoredDimensions()[1] *
          image.StoredDimensions()[2]);
        for (std::size_t v = 0; v < image.Labels.size(); ++v)
          image.Labels[v] = runs && v > 0 && random() % 5 != 0 ? image.Labels[v - 1]
                                                                : static_cast<std::int32_t>(random() % 4);
        if (indexed)
          cbc3d::IndexLabelRuns(image, 2);
        SCOPED_TRACE(::testing::Message() << "runs " << runs << " box " << box << " indexed " << indexed);
        EXPECT_GT(CheckRandomTets(image, random), 100);
      }
}
