#include "cbc3d/base/LabelImage.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "TestImages.h"

#include <algorithm>
#include <cmath>
#include <random>

TEST(LabelImage, IndexAndWorldRoundTripWithReflectedDirection)
{
  cbc3d::LabelImage image = Cube(4, 1);
  image.Origin = Eigen::Vector3d(10, -20, 5);
  image.Spacing = Eigen::Vector3d(0.5, 1.0, 2.5);
  // A rotation about z by 90 degrees, then x flipped: a reflection (det -1).
  Eigen::Matrix3d rotation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  image.Direction = Eigen::Vector3d(-1, 1, 1).asDiagonal() * rotation;
  EXPECT_NEAR(image.Direction.determinant(), -1.0, 1e-12);

  // Voxel (2,0,0) is 1 mm along the image's first axis: rotated to +y, not flipped.
  const Eigen::Vector3d world = image.IndexToWorld(Eigen::Vector3d(2, 0, 0));
  EXPECT_TRUE(world.isApprox(Eigen::Vector3d(10, -19, 5), 1e-12));
  // Voxel (0,1,0): 1 mm along the second axis: rotated to -x, then flipped to +x.
  EXPECT_TRUE(image.IndexToWorld(Eigen::Vector3d(0, 1, 0)).isApprox(Eigen::Vector3d(11, -20, 5), 1e-12));
  const Eigen::Vector3d index(1.25, 2.5, 3.0);
  EXPECT_TRUE(image.WorldToIndex(image.IndexToWorld(index)).isApprox(index, 1e-12));
  EXPECT_TRUE(cbc3d::ValidateLabelImage(image).IsOk());
}

TEST(LabelImage, TissueLabelsSkipEveryBackgroundLabel)
{
  cbc3d::LabelImage image = Cube(3, 0);
  image.Labels[0] = 1;
  image.Labels[5] = 128;
  image.Labels[7] = 5;
  image.BackgroundLabels = { 0, 1 };
  EXPECT_EQ(image.TissueLabels(), (std::vector<std::int32_t>{ 5, 128 }));
  std::array<int, 3> lower, upper;
  ASSERT_TRUE(cbc3d::TissueIndexBounds(image, lower, upper));
  EXPECT_EQ(lower, (std::array<int, 3>{ 1, 1, 0 })); // voxels 5 = (2,1,0) and 7 = (1,2,0)
  EXPECT_EQ(upper, (std::array<int, 3>{ 2, 2, 0 }));
}

TEST(LabelImage, ValidationNamesTheProblem)
{
  cbc3d::LabelImage flat = Cube(3, 1);
  flat.Dimensions = { 9, 3, 1 };
  EXPECT_NE(cbc3d::ValidateLabelImage(flat).GetMessage().find("3-D"), std::string::npos);

  const cbc3d::LabelImage empty = Cube(3, 0);
  EXPECT_NE(cbc3d::ValidateLabelImage(empty).GetMessage().find("no tissue"), std::string::npos);

  cbc3d::LabelImage sheared = Cube(3, 1);
  sheared.Direction(0, 1) = 0.3;
  EXPECT_NE(cbc3d::ValidateLabelImage(sheared).GetMessage().find("orthonormal"), std::string::npos);

  cbc3d::LabelImage negative = Cube(3, 1);
  negative.Spacing[2] = -1.0;
  EXPECT_NE(cbc3d::ValidateLabelImage(negative).GetMessage().find("spacing"), std::string::npos);
}

TEST(LabelImage, OrthonormalizeKeepsAReflectionAndMakesItExact)
{
  cbc3d::LabelImage image = Cube(2, 1);
  image.Direction << 0.0f, -1.0f, 0.0f, 0.70710677f, 0.0f, 0.70710677f, -0.70710677f, 0.0f, 0.70710677f;
  image.Direction.col(0) *= -1.0; // a float32 header's reflection
  cbc3d::OrthonormalizeDirection(image);
  EXPECT_LT((image.Direction.transpose() * image.Direction - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_NEAR(image.Direction.determinant(), -1.0, 1e-15);
  EXPECT_NEAR(image.Direction(1, 0), -std::sqrt(0.5), 1e-7);
}

TEST(LabelImage, TissueBoundsMatchEveryVoxelCheckedInAStoredBox)
{
  std::mt19937 random(7);
  for (int trial = 0; trial < 80; ++trial)
  {
    // A stored box somewhere inside a larger image, a few tissue voxels (or none) in it.
    cbc3d::LabelImage image;
    image.Dimensions = { 12, 10, 9 };
    image.StoredLower = { int(random() % 4), int(random() % 4), int(random() % 4) };
    image.StoredSize = { 2 + int(random() % 7), 2 + int(random() % 6), 2 + int(random() % 5) };
    image.BackgroundLabels = { 0, 9 };
    image.Labels.assign(std::size_t(image.StoredSize[0]) * image.StoredSize[1] * image.StoredSize[2], 0);
    const int tissue = int(random() % 4);
    for (int n = 0; n < tissue; ++n)
      image.Labels[random() % image.Labels.size()] = 3;
    for (int n = 0; n < 5; ++n)
      image.Labels[random() % image.Labels.size()] = 9; // background, not tissue
    std::array<int, 3> expectedLower = image.Dimensions, expectedUpper = { -1, -1, -1 };
    const std::array<int, 3> last = image.StoredUpper();
    for (int k = image.StoredLower[2]; k <= last[2]; ++k)
      for (int j = image.StoredLower[1]; j <= last[1]; ++j)
        for (int i = image.StoredLower[0]; i <= last[0]; ++i)
          if (image.IsTissue(image.LabelAt(i, j, k)))
          {
            const std::array<int, 3> at = { i, j, k };
            for (int a = 0; a < 3; ++a)
            {
              expectedLower[a] = std::min(expectedLower[a], at[a]);
              expectedUpper[a] = std::max(expectedUpper[a], at[a]);
            }
          }
    std::array<int, 3> lower, upper;
    EXPECT_EQ(cbc3d::TissueIndexBounds(image, lower, upper), expectedUpper[0] >= 0) << "trial " << trial;
    EXPECT_EQ(lower, expectedLower) << "trial " << trial;
    EXPECT_EQ(upper, expectedUpper) << "trial " << trial;
  }
}

TEST(LabelImage, RunsOfARowAreTheSameFromTheIndexOfRuns)
{
  // Random rows of a stored box, some with long runs: ForEachRun's runs, from the labels and
  // from the index of runs, are the row's labels, in order, adjacent runs differing.
  std::mt19937 random(5);
  cbc3d::LabelImage image;
  image.Dimensions = { 40, 12, 9 };
  image.StoredLower = { 3, 2, 1 };
  image.StoredSize = { 33, 9, 7 };
  image.Labels.resize(33 * 9 * 7);
  for (std::size_t v = 0; v < image.Labels.size(); ++v)
    image.Labels[v] = v % 33 != 0 && random() % 6 != 0 ? image.Labels[v - 1] : static_cast<std::int32_t>(random() % 3);
  cbc3d::LabelImage indexed = image;
  cbc3d::IndexLabelRuns(indexed, 3);
  ASSERT_EQ(indexed.RowRunFirst.size(), std::size_t(9 * 7 + 1));
  for (int trial = 0; trial < 500; ++trial)
  {
    const int j = 2 + int(random() % 9), k = 1 + int(random() % 7);
    int first = 3 + int(random() % 33), last = 3 + int(random() % 33);
    if (first > last)
      std::swap(first, last);
    for (const cbc3d::LabelImage* which : { &image, &indexed })
    {
      std::vector<std::int32_t> expanded;
      std::int32_t previous = -1;
      which->ForEachRun(j, k, first, last, [&](std::int32_t label, int voxels, int x) {
        EXPECT_EQ(x, first + int(expanded.size())); // where the run starts
        EXPECT_GT(voxels, 0);
        EXPECT_NE(label, previous);
        previous = label;
        expanded.insert(expanded.end(), std::size_t(voxels), label);
      });
      ASSERT_EQ(expanded.size(), std::size_t(last - first + 1));
      for (int i = first; i <= last; ++i)
        ASSERT_EQ(expanded[std::size_t(i - first)], image.LabelAt(i, j, k)) << i << " " << j << " " << k;
    }
  }
}

// The stored labels and the voxel owners are UninitializedVectors: AssignInParallel must write
// every element, whatever the size and the thread count, over whatever was there.
TEST(LabelImage, AssignInParallelWritesEveryElement)
{
  for (const std::size_t size : { std::size_t(0), std::size_t(1), std::size_t(65537), std::size_t(1) << 20 })
  {
    for (const int threads : { 1, 2, 3 })
    {
      cbc3d::UninitializedVector<std::int32_t> values(size / 2 + 3);
      std::fill(values.begin(), values.end(), 7);
      cbc3d::AssignInParallel(values, size, std::int32_t(-1), threads);
      ASSERT_EQ(values.size(), size);
      EXPECT_EQ(std::count(values.begin(), values.end(), -1), static_cast<std::ptrdiff_t>(size))
        << "size " << size << ", " << threads << " threads";
    }
  }
}
