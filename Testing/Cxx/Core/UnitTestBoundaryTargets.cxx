// Registration targets: boundary voxels, their label-sets, and where they sit.
#include "cbc3d/deformation/BoundaryTargets.h"

#include "TestImages.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
// A 4 x 4 x 4 block of label 3 (indices 2..5) in an 8^3 image of 1 mm voxels at the origin.
cbc3d::LabelImage Block()
{
  cbc3d::LabelImage image = Cube(8, 0);
  for (int k = 2; k < 6; ++k)
    for (int j = 2; j < 6; ++j)
      for (int i = 2; i < 6; ++i)
        image.Labels[image.VoxelIndex(i, j, k)] = 3;
  return image;
}
} // namespace

TEST(BoundaryTargets, EveryBoundaryVoxelOfABlockWithoutThinning)
{
  const auto targets = cbc3d::FindBoundaryTargets(Block(), cbc3d::TargetPattern::None);
  EXPECT_EQ(targets.size(), 64u - 8u); // all but the 2 x 2 x 2 core
  for (const auto& t : targets)
  {
    EXPECT_EQ(t.Labels, (cbc3d::LabelSet{ cbc3d::OutsideLabel, 3 }));
    EXPECT_EQ(t.Position, t.Position.array().round().matrix()); // voxel centres: whole mm here
  }
}

TEST(BoundaryTargets, FacePlacementPutsTargetsOnTheLabelBoundary)
{
  const cbc3d::LabelImage image = Block();
  const auto centres = cbc3d::FindBoundaryTargets(image, cbc3d::TargetPattern::None);
  const auto faces =
    cbc3d::FindBoundaryTargets(image, cbc3d::TargetPattern::None, cbc3d::TargetPlacement::VoxelFace);
  ASSERT_EQ(faces.size(), centres.size());
  int onAFace = 0;
  for (std::size_t t = 0; t < faces.size(); ++t)
  {
    EXPECT_EQ(faces[t].Labels, centres[t].Labels);
    const Eigen::Vector3d step = faces[t].Position - centres[t].Position;
    EXPECT_GT(step.norm(), 0.0);
    EXPECT_LE(step.norm(), 0.5 + 1e-12);
    // A voxel with one outside neighbour: its target is the centre of the shared face, on the
    // block's boundary plane x, y or z = 1.5 or 5.5.
    if (std::abs(step.norm() - 0.5) < 1e-12)
    {
      ++onAFace;
      int onPlane = 0;
      for (int a = 0; a < 3; ++a)
        onPlane += std::abs(faces[t].Position[a] - 1.5) < 1e-12 || std::abs(faces[t].Position[a] - 5.5) < 1e-12;
      EXPECT_EQ(onPlane, 1);
    }
  }
  EXPECT_EQ(onAFace, 6 * 4); // the 2 x 2 middle voxels of each of the six faces
}
