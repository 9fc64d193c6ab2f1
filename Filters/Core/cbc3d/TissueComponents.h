#ifndef cbc3d_TissueComponents_h
#define cbc3d_TissueComponents_h

#include "cbc3d/LabelImage.h"

#include <cstdint>
#include <vector>

namespace cbc3d
{
/// The 6-connected components of every tissue of a label image.
struct TissueComponents
{
  std::vector<std::int32_t> ComponentOfVoxel; // -1 for background voxels
  std::vector<std::int32_t> Label;            // per component: its tissue label
  std::vector<std::int64_t> Size;             // per component: its voxel count
};

/// Labels the face-connected components of every tissue (a breadth-first flood fill).
TissueComponents FindTissueComponents(const LabelImage& image);
} // namespace cbc3d

#endif
