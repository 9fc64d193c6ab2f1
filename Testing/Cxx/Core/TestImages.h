#ifndef cbc3d_TestImages_h
#define cbc3d_TestImages_h

#include "cbc3d/BCCLattice.h"
#include "cbc3d/LabelImage.h"

#include <gtest/gtest.h>

// Small label images for the core unit tests, and their lattices.

/// An n x n x n image of one label, spacing 1, origin 0, identity direction.
inline cbc3d::LabelImage Cube(int n, std::int32_t label)
{
  cbc3d::LabelImage image;
  image.Dimensions = { n, n, n };
  image.Labels.assign(static_cast<std::size_t>(n) * n * n, label);
  return image;
}

/// An n x n x n image of background 0 holding a ball of `label`: the voxels whose centres lie
/// within `radius` of the image's centre.
inline cbc3d::LabelImage BallImage(int n, double radius, std::int32_t label = 1)
{
  cbc3d::LabelImage image = Cube(n, 0);
  const Eigen::Vector3d centre = Eigen::Vector3d::Constant(0.5 * (n - 1));
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if ((Eigen::Vector3d(i, j, k) - centre).norm() <= radius)
          image.Labels[image.VoxelIndex(i, j, k)] = label;
  return image;
}

/// The BCC lattice of an image, cubes of `edge` mm.
inline cbc3d::TetMesh Lattice(const cbc3d::LabelImage& image, double edge)
{
  cbc3d::LatticeParams params;
  params.EdgeLength = edge;
  cbc3d::TetMesh lattice;
  EXPECT_TRUE(cbc3d::BuildBCCLattice(image, params, lattice).IsOk());
  return lattice;
}

#endif
