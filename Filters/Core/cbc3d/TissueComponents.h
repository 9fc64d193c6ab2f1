#ifndef cbc3d_TissueComponents_h
#define cbc3d_TissueComponents_h

#include "cbc3d/LabelImage.h"

#include <cstdint>
#include <vector>

namespace cbc3d
{
/// The 6-connected components of every tissue of a label image, as runs along x: no map the
/// size of the image (on a 471 M voxel image each such map was 430 MB to fill).
struct TissueComponents
{
  std::vector<std::int32_t> Label; // per component: its tissue label
  std::vector<std::int64_t> Size;  // per component: its voxel count
  /// The tissue voxels as runs of one label along x (first and last voxel index, inclusive,
  /// and the component), ascending by voxel.
  struct Run
  {
    std::int64_t First, Last;
    std::int32_t Component;
  };
  std::vector<Run> Runs;

  /// Calls visit(voxel, component) for every tissue voxel, ascending.
  template <typename Visit>
  void ForEachVoxel(Visit&& visit) const
  {
    for (const Run& run : this->Runs)
      for (std::int64_t v = run.First; v <= run.Last; ++v)
        visit(v, run.Component);
  }
  /// The component of a voxel (a stored voxel index), or -1 for a background voxel.
  std::int32_t ComponentOf(std::int64_t voxel) const;
};

/// Labels the face-connected components of every tissue: runs of one label in neighbouring
/// rows that overlap join (disjoint sets over the runs, so the cost follows the runs, not the
/// voxels). Components are numbered in the order of their first voxel.
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
