#ifndef cbc3d_TissueComponents_h
#define cbc3d_TissueComponents_h

#include "cbc3d/base/LabelImage.h"

#include <cstdint>
#include <vector>

namespace cbc3d
{
/// Face-connected components of some voxels of a label image, as runs along x: no map the size
/// of the image (on a 471 M voxel image each such map was 430 MB to fill).
struct RunComponents
{
  std::vector<std::int64_t> Size; // per component: its voxel count
  /// The voxels as runs along x (first and last voxel index, inclusive, and the component),
  /// ascending by voxel.
  struct Run
  {
    std::int64_t First, Last;
    std::int32_t Component;
  };
  std::vector<Run> Runs;
  /// Over MPI ranks (RankPasses::JoinComponents): per component of this piece, its number in the
  /// whole image, shared by the pieces of one component. Empty otherwise.
  std::vector<std::int64_t> WholeId;

  /// Calls visit(voxel, component) for every voxel, ascending.
  template <typename Visit>
  void ForEachVoxel(Visit&& visit) const
  {
    for (const Run& run : this->Runs)
      for (std::int64_t v = run.First; v <= run.Last; ++v)
        visit(v, run.Component);
  }
  /// The component of a voxel (a stored voxel index), or -1 for a voxel of none.
  std::int32_t ComponentOf(std::int64_t voxel) const;
};

/// The 6-connected components of every tissue of a label image.
struct TissueComponents : RunComponents
{
  std::vector<std::int32_t> Label; // per component: its tissue label
};

/// Labels the face-connected components of every tissue: runs of one label in neighbouring
/// rows that overlap join (disjoint sets over the runs, so the cost follows the runs, not the
/// voxels). Components are numbered in the order of their first voxel.
TissueComponents FindTissueComponents(const LabelImage& image);

/// The 6-connected components of the background (all background labels together), within the
/// tissues' bounding box and one voxel around it (the rest is all outside).
struct BackgroundComponents : RunComponents
{
  std::vector<char> TouchesBorder; // per component: it reaches that layer, so it is the outside
};

/// Labels the face-connected components of the background as FindTissueComponents does the
/// tissues'; the ones that reach the layer around the tissues' box (or the image border) are the
/// outside (TouchesBorder), the others cavities. On a piece of a larger image (HasLatticeBox),
/// a side where the whole image's tissue goes on is no border: what lies beyond is another
/// piece's to say (RankPasses::JoinComponents).
BackgroundComponents FindBackgroundComponents(const LabelImage& image);
} // namespace cbc3d

#endif
