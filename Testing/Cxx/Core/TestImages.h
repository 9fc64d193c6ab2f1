#ifndef cbc3d_TestImages_h
#define cbc3d_TestImages_h

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/lattice/BCCLattice.h"

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

/// Paints `label` on the voxels whose centres lie within `radius` of `centre` (world space; the
/// same as index space for the images above).
inline void PaintBall(cbc3d::LabelImage& image, const Eigen::Vector3d& centre, double radius, std::int32_t label)
{
  const auto& d = image.Dimensions;
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i)
        if ((image.IndexToWorld(Eigen::Vector3d(i, j, k)) - centre).norm() <= radius)
          image.Labels[image.VoxelIndex(i, j, k)] = label;
}

/// An n x n x n image of background 0 holding a ball of `label` around the image's centre.
inline cbc3d::LabelImage BallImage(int n, double radius, std::int32_t label = 1)
{
  cbc3d::LabelImage image = Cube(n, 0);
  PaintBall(image, Eigen::Vector3d::Constant(0.5 * (n - 1)), radius, label);
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
