// The tissue and background components of label images against a flood fill over voxels,
// and the sound labels' stray pieces and image regions built on them.
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/sampling/TissueComponents.h"
#include "cbc3d/soundlabels/ImageRegions.h"
#include "cbc3d/soundlabels/StrayComponents.h"

#include "TestImages.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

TEST(TissueComponents, FaceConnectedOnly)
{
  cbc3d::LabelImage image = Cube(6, 0);
  // Two voxels of label 1 touching only along an edge: two components; a 2x2x1 plate of label
  // 1 elsewhere: one; a voxel of label 5 face-adjacent to the plate: its own component.
  image.Labels[image.VoxelIndex(0, 0, 0)] = 1;
  image.Labels[image.VoxelIndex(1, 1, 0)] = 1;
  for (int j = 3; j < 5; ++j)
    for (int i = 3; i < 5; ++i)
      image.Labels[image.VoxelIndex(i, j, 4)] = 1;
  image.Labels[image.VoxelIndex(3, 3, 5)] = 5;
  const cbc3d::TissueComponents components = cbc3d::FindTissueComponents(image);
  ASSERT_EQ(components.Label.size(), 4u);
  EXPECT_EQ(components.Label, (std::vector<std::int32_t>{ 1, 1, 1, 5 }));
  EXPECT_EQ(components.Size, (std::vector<std::int64_t>{ 1, 1, 4, 1 }));
  EXPECT_EQ(components.ComponentOf(image.VoxelIndex(4, 4, 4)), 2);
  EXPECT_EQ(components.ComponentOf(image.VoxelIndex(3, 3, 5)), 3);
  EXPECT_EQ(components.ComponentOf(image.VoxelIndex(5, 5, 5)), -1);
  EXPECT_EQ(components.ComponentOf(image.VoxelIndex(0, 0, 0)), 0);
}

namespace
{
// The components by a flood fill over voxels, seeded in raster order: the definition. Tissue
// voxels join voxels of their label; with `background`, background voxels join each other
// (all background labels together) within the box [lower, upper], and `face` tells for each
// component whether it reaches the box's faces.
std::vector<std::int32_t> FloodEveryVoxel(const cbc3d::LabelImage& image, std::vector<std::int64_t>& sizes,
  bool background = false, std::array<int, 3> lower = {}, std::array<int, 3> upper = {},
  std::vector<char>* face = nullptr)
{
  const auto& n = image.StoredDimensions();
  if (!background)
    for (int axis = 0; axis < 3; ++axis)
    {
      lower[axis] = image.StoredLower[axis];
      upper[axis] = image.StoredLower[axis] + n[axis] - 1;
    }
  auto member = [&](std::int64_t v) {
    const std::array<int, 3> at = image.VoxelCoordinates(v);
    for (int axis = 0; axis < 3; ++axis)
      if (at[axis] < lower[axis] || at[axis] > upper[axis])
        return false;
    return background ? image.IsBackground(image.Labels[v]) : image.IsTissue(image.Labels[v]);
  };
  std::vector<std::int32_t> component(image.Labels.size(), -1);
  std::int32_t count = 0;
  for (std::int64_t seed = 0; seed < std::int64_t(image.Labels.size()); ++seed)
  {
    if (component[seed] >= 0 || !member(seed))
      continue;
    if (face)
      face->push_back(0);
    std::vector<std::int64_t> stack = { seed };
    component[seed] = count;
    sizes.push_back(0);
    while (!stack.empty())
    {
      const std::int64_t v = stack.back();
      stack.pop_back();
      ++sizes.back();
      const std::array<int, 3> at = image.VoxelCoordinates(v);
      for (int axis = 0; axis < 3; ++axis)
        for (const int step : { -1, 1 })
        {
          std::array<int, 3> next = at;
          next[axis] += step;
          if (next[axis] < lower[axis] || next[axis] > upper[axis])
          {
            if (face)
              face->back() = 1;
            continue;
          }
          const std::int64_t w = image.VoxelIndex(next[0], next[1], next[2]);
          if (component[w] < 0 && member(w) && (background || image.Labels[w] == image.Labels[v]))
          {
            component[w] = count;
            stack.push_back(w);
          }
        }
    }
    ++count;
  }
  return component;
}

// Random blobs of the labels in `pick` (0 and 9 the background) in a stored box of a larger
// image: runs along x that go on with probability 1 - 1 / change, or take the label below.
cbc3d::LabelImage RandomBlobs(std::mt19937& random, int change, const std::array<std::int32_t, 5>& pick)
{
  cbc3d::LabelImage image;
  image.Dimensions = { 24, 20, 18 };
  image.StoredLower = { 2, 1, 3 };
  image.StoredSize = { 19, 16, 12 };
  image.BackgroundLabels = { 0, 9 };
  image.Labels.resize(19 * 16 * 12);
  for (std::size_t v = 0; v < image.Labels.size(); ++v)
  {
    const bool keep = v % 19 != 0 && int(random() % change) != 0;
    const std::int32_t fresh = pick[random() % 5];
    image.Labels[v] = keep ? image.Labels[v - 1] : (v >= 19 * 16 && random() % 2 ? image.Labels[v - 19 * 16] : fresh);
  }
  return image;
}
} // namespace

TEST(TissueComponents, RunsJoinAsAFloodFillOverVoxels)
{
  // Random blobs of three tissues and two background labels in a stored box, with and without
  // the index of runs: every voxel's component, the numbering and the sizes of a voxel flood.
  std::mt19937 random(11);
  for (int trial = 0; trial < 40; ++trial)
  {
    cbc3d::LabelImage image = RandomBlobs(random, 2 + trial % 5, { 0, 9, 1, 2, 3 });
    std::vector<std::int64_t> sizes;
    const std::vector<std::int32_t> expected = FloodEveryVoxel(image, sizes);
    cbc3d::LabelImage indexed = image;
    cbc3d::IndexLabelRuns(indexed, 2);
    for (const cbc3d::LabelImage* which : { &image, &indexed })
    {
      const cbc3d::TissueComponents components = cbc3d::FindTissueComponents(*which);
      ASSERT_EQ(components.Size, sizes) << "trial " << trial;
      std::vector<std::int32_t> found(image.Labels.size(), -1);
      components.ForEachVoxel([&](std::int64_t v, std::int32_t c) { found[v] = c; });
      ASSERT_EQ(found, expected) << "trial " << trial;
      for (std::size_t c = 0; c < components.Label.size(); ++c)
        EXPECT_EQ(components.Label[c], image.Labels[std::find(expected.begin(), expected.end(), std::int32_t(c)) - expected.begin()]);
      for (std::int64_t v = 0; v < std::int64_t(image.Labels.size()); v += 5)
        ASSERT_EQ(components.ComponentOf(v), expected[v]);
    }
  }
}

TEST(TissueComponents, BackgroundRunsJoinAsAFloodFillOverVoxels)
{
  // Random blobs as above: the background's components within the tissues' box and one voxel
  // around it, their sizes, numbering and reaching the box's faces (the outside), as a voxel
  // flood of the same box finds them; runs of the two background labels side by side are one.
  std::mt19937 random(12);
  for (int trial = 0; trial < 40; ++trial)
  {
    cbc3d::LabelImage image = RandomBlobs(random, 2 + trial % 5, { 0, 9, 1, 1, 2 });
    std::array<int, 3> lower = { 1 << 20, 1 << 20, 1 << 20 }, upper = { -1, -1, -1 };
    for (std::int64_t v = 0; v < std::int64_t(image.Labels.size()); ++v)
      if (image.IsTissue(image.Labels[v]))
        for (int axis = 0; axis < 3; ++axis)
        {
          lower[axis] = std::min(lower[axis], image.VoxelCoordinates(v)[axis]);
          upper[axis] = std::max(upper[axis], image.VoxelCoordinates(v)[axis]);
        }
    ASSERT_GE(upper[0], 0) << "trial " << trial;
    for (int axis = 0; axis < 3; ++axis)
    {
      lower[axis] = std::max(lower[axis] - 1, image.StoredLower[axis]);
      upper[axis] = std::min(upper[axis] + 1, image.StoredLower[axis] + image.StoredSize[axis] - 1);
    }
    std::vector<std::int64_t> sizes;
    std::vector<char> face;
    const std::vector<std::int32_t> expected = FloodEveryVoxel(image, sizes, true, lower, upper, &face);
    ASSERT_GT(std::count(face.begin(), face.end(), 0), 0) << "trial " << trial << ": no cavity to test";
    cbc3d::LabelImage indexed = image;
    cbc3d::IndexLabelRuns(indexed, 2);
    for (const cbc3d::LabelImage* which : { &image, &indexed })
    {
      const cbc3d::BackgroundComponents gaps = cbc3d::FindBackgroundComponents(*which);
      ASSERT_EQ(gaps.Size, sizes) << "trial " << trial;
      EXPECT_EQ(gaps.TouchesBorder, face) << "trial " << trial;
      std::vector<std::int32_t> found(image.Labels.size(), -1);
      gaps.ForEachVoxel([&](std::int64_t v, std::int32_t c) { found[v] = c; });
      ASSERT_EQ(found, expected) << "trial " << trial;
    }
  }
}

// Two pieces of tissue 1 (tets 0 and 2, with background tet 1 between them) share one image
// component of 11 voxels: the piece that owns more of its voxels stands for it, the other goes
// to the background. The voxels' order puts the deciding ones last, or interleaves the owners,
// so that counting stretches of one owner instead of voxels, or losing the last stretch, shows.
TEST(StrayComponents, ThePieceOwningMostOfAComponentsVoxelsStays)
{
  const std::vector<cbc3d::Tet> tets(3, cbc3d::Tet{ 0, 1, 2, 3 }); // geometry is not read
  const std::vector<cbc3d::TetNeighbours> across = { { 1, -1, -1, -1 }, { 0, 2, -1, -1 }, { 1, -1, -1, -1 } };
  cbc3d::TissueComponents components;
  components.Label = { 1 };
  components.Size = { 11 };
  components.Runs = { { 0, 10, 0 } };
  cbc3d::ImageRegions regions;
  regions.Tissues = &components;
  regions.ClassOfRegion = { 1 };
  regions.Speck = { 0 };
  const cbc3d::ClassVotes votes = [](std::int64_t, std::int32_t) { return std::int64_t(0); };
  struct Case
  {
    std::vector<std::int32_t> Owners;
    std::int64_t Stray; // the tet given away
  };
  const std::vector<Case> cases = { { { 0, 0, 0, 0, 0, 2, 2, 2, 2, 2, 2 }, 0 },
    { { 2, 2, 2, 2, 2, 0, 0, 0, 0, 0, 0 }, 2 }, { { 0, 2, 0, 2, 0, 2, 0, 2, 2, 2, 0 }, 0 } };
  for (const Case& c : cases)
  {
    cbc3d::VoxelOwners owners(c.Owners.begin(), c.Owners.end());
    std::vector<std::int32_t> classes = { 1, 0, 1 };
    std::vector<std::int64_t> changed;
    EXPECT_EQ(cbc3d::RemoveStrayComponents(tets, across, 0, votes, owners, regions, classes, changed), 1);
    EXPECT_EQ(changed, std::vector<std::int64_t>{ c.Stray });
    EXPECT_EQ(classes[c.Stray], 0);
    EXPECT_EQ(classes[2 - c.Stray], 1);
  }
}

// A hollow cube: tets smaller than a voxel own no voxel centre, yet the repair must know which
// background they stand for. They are judged by the voxels under their points; a tet that owns
// background voxels is judged by those, wherever it lies.
TEST(ImageRegions, TetsWithoutVoxelCentresTakeTheRegionOfTheVoxelsUnderThem)
{
  cbc3d::LabelImage image = Cube(12, 0);
  for (int k = 2; k <= 9; ++k)
    for (int j = 2; j <= 9; ++j)
      for (int i = 2; i <= 9; ++i)
        image.Labels[image.VoxelIndex(i, j, k)] = (i < 4 || i > 7 || j < 4 || j > 7 || k < 4 || k > 7) ? 1 : 0;
  const cbc3d::TissueComponents components = cbc3d::FindTissueComponents(image);
  const cbc3d::ImageRegions regions = cbc3d::FindImageRegions(image, components, 8, 0);
  ASSERT_TRUE(regions.HasCavity());
  const std::int32_t cavity = regions.RegionOfGap[regions.Gaps.ComponentOf(image.VoxelIndex(5, 5, 5))];
  ASSERT_GE(cavity, 0);
  // A tet of edge 0.4 voxel at each place, clear of every voxel centre.
  std::vector<Eigen::Vector3d> points;
  std::vector<cbc3d::Tet> tets;
  for (const Eigen::Vector3d corner : { Eigen::Vector3d(5.3, 5.3, 5.3), Eigen::Vector3d(0.3, 0.3, 0.3),
         Eigen::Vector3d(2.3, 5.3, 5.3), Eigen::Vector3d(10.3, 10.3, 10.3) })
  {
    const cbc3d::PointId first = static_cast<cbc3d::PointId>(points.size());
    points.insert(points.end(), { corner, corner + Eigen::Vector3d(0.4, 0, 0), corner + Eigen::Vector3d(0, 0.4, 0),
                                  corner + Eigen::Vector3d(0, 0, 0.4) });
    tets.push_back({ first, first + 1, first + 2, first + 3 });
  }
  // The last tet, outside the shell, owns a voxel of the cavity (and one of the outside).
  cbc3d::VoxelOwners owners;
  owners.assign(image.Labels.size(), -1);
  owners[image.VoxelIndex(6, 6, 6)] = 3;
  owners[image.VoxelIndex(6, 6, 7)] = 3;
  owners[image.VoxelIndex(11, 11, 11)] = 3;
  const std::vector<std::int32_t> region = cbc3d::BackgroundRegionOfTets(image, regions, owners, points, tets, 2);
  ASSERT_EQ(region.size(), tets.size());
  EXPECT_EQ(region[0], cavity) << "inside the cavity";
  EXPECT_EQ(region[1], cbc3d::OutsideRegion) << "beyond the tissues' box";
  EXPECT_EQ(region[2], cbc3d::NoRegion) << "inside the shell's wall";
  EXPECT_EQ(region[3], cavity) << "owns two cavity voxels and one of the outside";
}
