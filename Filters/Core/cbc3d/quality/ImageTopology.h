#ifndef cbc3d_ImageTopology_h
#define cbc3d_ImageTopology_h

#include "cbc3d/base/LabelImage.h"

#include <cstdint>
#include <map>

namespace cbc3d
{
/// The Euler characteristic V - E + F of the voxel-face surface of each tissue of an image and
/// of the whole body (the union of the tissues). The surface of a set of voxels is the voxel
/// faces between a voxel of the set and one that is not (beyond the image counts as not), and
/// V and E count the distinct voxel corners and voxel edges of those faces. A ball has 2, a
/// solid torus 0, a thick spherical shell 4; two cubes meeting along an edge or at a corner 3.
///
/// Where voxels of a set touch only along an edge or at a corner (a pinch), that surface is not
/// a 2-manifold, and a manifold surface round the same voxels must either join the two sides
/// there or part them. The two extreme readings are the Euler characteristics of the surface of
/// the voxels joined through faces, edges and corners (every pinch joined: twice that of the
/// union of closed voxels) and of the voxels joined through faces only (every pinch parted:
/// twice that of the complex of voxel centres, face-neighbour edges, squares and cubes). The
/// voxel-face figure is exactly their mean; the three agree where the set has no pinch.
struct ImageTopology
{
  std::int64_t WholeSurfaceEuler = 0;
  std::int64_t WholePinchesPartedEuler = 0;
  std::map<std::int32_t, std::int64_t> TissueSurfaceEuler; // keyed by label value
  std::map<std::int32_t, std::int64_t> TissuePinchesPartedEuler;

  /// The joined reading, from the other two (the voxel-face figure is their mean).
  static std::int64_t PinchesJoined(std::int64_t surfaceEuler, std::int64_t partedEuler)
  {
    return 2 * surfaceEuler - partedEuler;
  }
  std::int64_t WholePinchesJoinedEuler() const
  {
    return PinchesJoined(this->WholeSurfaceEuler, this->WholePinchesPartedEuler);
  }
  /// A tissue's joined reading; the label must be one of TissueSurfaceEuler's.
  std::int64_t TissuePinchesJoinedEuler(std::int32_t label) const
  {
    return PinchesJoined(this->TissueSurfaceEuler.at(label), this->TissuePinchesPartedEuler.at(label));
  }
};

/// Every tissue's and the whole body's surface Euler characteristic. Each set is scanned over
/// its bounding box only, a slab of slices per thread with two slices of corner codes each
/// (0 threads: the OpenMP default). The same result for any thread count.
ImageTopology MeasureImageTopology(const LabelImage& image, int numberOfThreads = 0);

/// Every tissue's surface Euler characteristic (MeasureImageTopology without the whole body).
std::map<std::int32_t, std::int64_t> ImageSurfaceEuler(const LabelImage& image, int numberOfThreads = 0);
} // namespace cbc3d

#endif
