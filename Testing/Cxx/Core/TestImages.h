#ifndef cbc3d_TestImages_h
#define cbc3d_TestImages_h

#include "cbc3d/LabelImage.h"

// Small label images for the core unit tests.

/// An n x n x n image of one label, spacing 1, origin 0, identity direction.
inline cbc3d::LabelImage Cube(int n, std::int32_t label)
{
  cbc3d::LabelImage image;
  image.Dimensions = { n, n, n };
  image.Labels.assign(static_cast<std::size_t>(n) * n * n, label);
  return image;
}

#endif
