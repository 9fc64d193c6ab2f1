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
  /// The tissue voxels as runs along x (first and last voxel index, inclusive), ascending:
  /// loops over the tissue visit neither a mostly empty image nor a list of every voxel (on
  /// a 471 M voxel image that list alone was 400 MB).
  struct Run
  {
    std::int64_t First, Last;
  };
  std::vector<Run> Runs;

  /// Calls visit(voxel) for every tissue voxel, ascending.
  template <typename Visit>
  void ForEachVoxel(Visit&& visit) const
  {
    for (const Run& run : this->Runs)
      for (std::int64_t v = run.First; v <= run.Last; ++v)
        visit(v);
  }
};

/// Labels the face-connected components of every tissue (a breadth-first flood fill).
TissueComponents FindTissueComponents(const LabelImage& image);

/// The 6-connected components of the background (all background labels together).
struct BackgroundComponents
{
  std::vector<std::int32_t> ComponentOfVoxel; // -1 for tissue voxels and beyond the layer
  std::vector<std::int64_t> Size;             // per component: its voxel count within the box
  std::vector<char> TouchesBorder;            // per component: it is the outside
};

/// Labels the face-connected components of the background within the tissues' bounding box and
/// one voxel around it (the rest is all outside); the ones that reach that layer or the image
/// border are the outside (TouchesBorder), the others cavities. Voxels beyond the layer are -1.
BackgroundComponents FindBackgroundComponents(const LabelImage& image);
} // namespace cbc3d

#endif
