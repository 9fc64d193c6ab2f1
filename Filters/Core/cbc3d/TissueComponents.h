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

/// The 6-connected components of the background (all background labels together).
struct BackgroundComponents
{
  std::vector<std::int32_t> ComponentOfVoxel; // -1 for tissue voxels
  std::vector<std::int64_t> Size;             // per component: its voxel count
  std::vector<char> TouchesBorder;            // per component: it reaches the image border
};

/// Labels the face-connected components of the background; the ones on the image border are
/// the outside, the others cavities.
BackgroundComponents FindBackgroundComponents(const LabelImage& image);
} // namespace cbc3d

#endif
