#include "cbc3d/quality/SurfaceDistance.h"
#include "cbc3d/sampling/SurfacePoints.h"

#include <gtest/gtest.h>

#include <array>
#include <random>

#include "TestImages.h"

TEST(SurfacePoints, BoundaryVoxelsOfABlockAreAllButItsCore)
{
  cbc3d::LabelImage image = Cube(7, 0);
  // A 3x3x3 block of label 4 touching the image border at x = 0, and a lone voxel of label 9.
  for (int k = 2; k <= 4; ++k)
    for (int j = 2; j <= 4; ++j)
      for (int i = 0; i <= 2; ++i)
        image.Labels[image.VoxelIndex(i, j, k)] = 4;
  image.Labels[image.VoxelIndex(5, 5, 5)] = 9;
  const auto boundary = cbc3d::TissueBoundaryVoxelCentres(image, 2);
  ASSERT_EQ(boundary.size(), 2u);
  // The block's middle layer i = 0 touches the border: its centre voxel (0,3,3) counts too, so
  // only (1,3,3) is interior.
  EXPECT_EQ(boundary.at(4).size(), 26u);
  EXPECT_EQ(boundary.at(9).size(), 1u);
  EXPECT_TRUE(boundary.at(9)[0].isApprox(Eigen::Vector3d(5, 5, 5)));
  for (const auto& centre : boundary.at(4))
    EXPECT_FALSE(centre.isApprox(Eigen::Vector3d(1, 3, 3)));
}

TEST(SurfacePoints, SurfaceVerticesIncludeInterfacesAndSkipInteriorVertices)
{
  // The 8 tets of an octahedron (vertices +-x, +-y, +-z) around the origin, label 1 where
  // z > 0 and label 2 where z < 0.
  cbc3d::TetMesh mesh;
  mesh.Points = { { 0, 0, 0 }, { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 },
    { 0, 0, -1 } };
  const int xs[2] = { 1, 2 }, ys[2] = { 3, 4 }, zs[2] = { 5, 6 };
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int c = 0; c < 2; ++c)
      {
        mesh.Tets.push_back({ 0, xs[a], ys[b], zs[c] });
        mesh.Labels.push_back(c == 0 ? 1 : 2);
      }
  const auto surface = cbc3d::TissueSurfaceVertices(mesh);
  ASSERT_EQ(surface.size(), 2u);
  // Label 1 (the upper half): its surface is the four upper faces plus the interface z = 0,
  // so every vertex but the lower apex 6, the origin included.
  EXPECT_EQ(surface.at(1), (std::vector<cbc3d::PointId>{ 0, 1, 2, 3, 4, 5 }));
  EXPECT_EQ(surface.at(2), (std::vector<cbc3d::PointId>{ 0, 1, 2, 3, 4, 6 }));

  // With one label everywhere the origin is interior.
  std::fill(mesh.Labels.begin(), mesh.Labels.end(), 3);
  EXPECT_EQ(cbc3d::TissueSurfaceVertices(mesh).at(3), (std::vector<cbc3d::PointId>{ 1, 2, 3, 4, 5, 6 }));
}

TEST(SurfaceDistance, SummaryOfKnownDistances)
{
  std::vector<double> aToB = { 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20 };
  std::vector<double> bToA = { 0.5, 30.0 };
  const cbc3d::SurfaceDistanceSummary s = cbc3d::SummarizeSurfaceDistances(aToB, bToA);
  EXPECT_DOUBLE_EQ(s.AToB, 20.0);
  EXPECT_DOUBLE_EQ(s.BToA, 30.0);
  EXPECT_DOUBLE_EQ(s.Hausdorff, 30.0);
  // Nearest rank: the 19th of 20 values for A, the 2nd of 2 for B.
  EXPECT_DOUBLE_EQ(s.Percentile95, 30.0);
  EXPECT_DOUBLE_EQ(s.Mean, (210.0 + 30.5) / 22.0);
  std::vector<double> only = { 4, 1, 3, 2, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20 };
  std::vector<double> same = only;
  EXPECT_DOUBLE_EQ(cbc3d::SummarizeSurfaceDistances(only, same).Percentile95, 19.0);
}

TEST(SurfaceDistance, TheWholeMeshsPercentileCountsEverySample)
{
  // A large tissue 1 mm off its boundary (100 samples each way) and a speck 22 mm off (2 each
  // way): of the 102 samples each way, the 97th (the nearest-rank 95th percentile) is 1 mm, where
  // the larger of the tissues' own percentiles would say 22 mm.
  const std::vector<double> largeA(100, 1.0), largeB(100, 1.0), speckA(2, 22.0), speckB(2, 22.0);
  const cbc3d::SurfaceDistanceSummary all =
    cbc3d::SummarizeSurfaceDistancesTogether({ &largeA, &speckA }, { &largeB, &speckB });
  EXPECT_DOUBLE_EQ(all.Percentile95, 1.0);
  EXPECT_DOUBLE_EQ(all.Hausdorff, 22.0);
  EXPECT_DOUBLE_EQ(all.Mean, (200.0 * 1.0 + 4.0 * 22.0) / 204.0);
  // With the speck at 6 of 106 samples each way (over 5%), the percentile is the speck's.
  const std::vector<double> bigSpeck(6, 22.0);
  EXPECT_DOUBLE_EQ(cbc3d::SummarizeSurfaceDistancesTogether({ &largeA, &bigSpeck }, { &largeB, &bigSpeck }).Percentile95, 22.0);
}

TEST(SurfacePoints, BoundaryVoxelsRunByRunAreThoseOfAVoxelByVoxelScan)
{
  // Random blobs of three tissues and two background labels, in a stored box that is the whole
  // image or leaves a margin of background on some sides, with and without the index of runs:
  // a tissue voxel is a boundary voxel where a 6-neighbour holds another label or the image
  // ends there.
  std::mt19937 random(5);
  for (int trial = 0; trial < 30; ++trial)
  {
    cbc3d::LabelImage image;
    image.Dimensions = { 21, 17, 15 };
    const bool margin = trial % 2 == 1;
    image.StoredLower = margin ? std::array<int, 3>{ 0, 2, 1 } : std::array<int, 3>{ 0, 0, 0 };
    image.StoredSize = margin ? std::array<int, 3>{ 19, 15, 14 } : image.Dimensions;
    image.BackgroundLabels = { 0, 9 };
    const auto& s = image.StoredSize;
    image.Labels.resize(std::size_t(s[0]) * s[1] * s[2]);
    const int change = 2 + trial % 4;
    for (std::size_t v = 0; v < image.Labels.size(); ++v)
    {
      const std::int32_t fresh = std::array<std::int32_t, 5>{ 0, 9, 1, 2, 3 }[random() % 5];
      const bool keep = v % s[0] != 0 && int(random() % change) != 0;
      image.Labels[v] = keep ? image.Labels[v - 1] : (v >= std::size_t(s[0]) * s[1] && random() % 2 ? image.Labels[v - s[0] * s[1]] : fresh);
    }
    if (margin) // background around the tissue wherever the box stops short of the image's end
      for (int k = 0; k < s[2]; ++k)
        for (int j = 0; j < s[1]; ++j)
          for (int i = 0; i < s[0]; ++i)
          {
            const int x = i + image.StoredLower[0], y = j + image.StoredLower[1], z = k + image.StoredLower[2];
            if ((i == s[0] - 1 && x < image.Dimensions[0] - 1) || (j == 0 && y > 0) || (j == s[1] - 1 && y < image.Dimensions[1] - 1) ||
              (k == 0 && z > 0) || (k == s[2] - 1 && z < image.Dimensions[2] - 1))
              image.Labels[image.VoxelIndex(x, y, z)] = 0;
          }
    cbc3d::TissueVoxels expected;
    const auto& d = image.Dimensions;
    for (int z = 0; z < d[2]; ++z)
      for (int y = 0; y < d[1]; ++y)
        for (int x = 0; x < d[0]; ++x)
        {
          const std::int32_t label = image.LabelOf(x, y, z);
          if (!image.IsTissue(label))
            continue;
          bool boundary = x == 0 || y == 0 || z == 0 || x == d[0] - 1 || y == d[1] - 1 || z == d[2] - 1;
          const int steps[6][3] = { { -1, 0, 0 }, { 1, 0, 0 }, { 0, -1, 0 }, { 0, 1, 0 }, { 0, 0, -1 }, { 0, 0, 1 } };
          for (const auto& step : steps)
            boundary = boundary || image.LabelOf(x + step[0], y + step[1], z + step[2]) != label;
          if (boundary)
            expected[label].push_back(image.VoxelIndex(x, y, z));
        }
    cbc3d::LabelImage indexed = image;
    cbc3d::IndexLabelRuns(indexed, 2);
    for (const cbc3d::LabelImage* which : { &image, &indexed })
      for (const int threads : { 1, 3 })
        ASSERT_EQ(cbc3d::TissueBoundaryVoxels(*which, threads), expected) << "trial " << trial;
  }
}
