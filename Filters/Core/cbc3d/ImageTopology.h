#ifndef cbc3d_ImageTopology_h
#define cbc3d_ImageTopology_h

#include "cbc3d/LabelImage.h"

#include <cstdint>
#include <map>

namespace cbc3d
{
/// The Euler characteristic V - E + F of the voxel-face surface of each tissue of an image and
/// of the whole body (the union of the tissues). The surface of a set of voxels is the voxel
/// faces between a voxel of the set and one that is not (beyond the image counts as not), and
/// V and E count the distinct voxel corners and voxel edges of those faces. A ball has 2, a
/// solid torus 0, a thick spherical shell 4; two cubes meeting along an edge or at a corner 3.
struct ImageTopology
{
  std::int64_t WholeSurfaceEuler = 0;
  std::map<std::int32_t, std::int64_t> TissueSurfaceEuler; // keyed by label value
};

/// Every tissue's and the whole body's surface Euler characteristic. Each set is scanned over
/// its bounding box only, a slab of slices per thread with two slices of corner codes each
/// (0 threads: the OpenMP default). The same result for any thread count.
ImageTopology MeasureImageTopology(const LabelImage& image, int numberOfThreads = 0);

/// Every tissue's surface Euler characteristic (MeasureImageTopology without the whole body).
std::map<std::int32_t, std::int64_t> ImageSurfaceEuler(const LabelImage& image, int numberOfThreads = 0);
} // namespace cbc3d

#endif
