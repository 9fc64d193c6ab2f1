#ifndef cbc3d_RankPasses_h
#define cbc3d_RankPasses_h

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/sampling/TissueComponents.h"

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

namespace cbc3d
{
/// How the refinement passes on one rank's piece of an image take the whole image's decisions
/// (vtkCBC3DMesher over MPI ranks). Each tissue's voxel fidelity counts the voxels and tets of
/// this rank's slab alone and is summed over the ranks; so is the boundary-distance progress;
/// a component of a tissue or of the background is the whole image's, joined across the slabs;
/// and the passes, and the rounds for edge limits, end on every rank together. Each function is
/// a collective call: every rank calls it as often, in the same order (a rank without tissue
/// runs the same refinement on no tets).
struct RankPasses
{
  int Axis = 2;       // the image axis across the slabs
  double Lower = 0.0; // this rank's slab: mm along Axis from voxel 0 of the piece, [Lower, Upper)
  double Upper = 0.0;
  /// The sum of `sum` and the largest `largest` over the ranks.
  std::function<void(double& sum, double& largest)> SumAndMax;
  /// Whether any rank says yes.
  std::function<bool(bool)> Any;
  /// Every rank's values, in rank order.
  std::function<std::vector<double>(const std::vector<double>&)> AllValues;
  /// Joins the components of this rank's piece of `image` (a tissue's, or the background's) with
  /// the other ranks' into the whole image's: Size becomes the whole component's voxel count,
  /// WholeId its number, and `outside` (the background's, when given) whether any part of it
  /// reaches the outside.
  std::function<void(const LabelImage& image, RunComponents& components, std::vector<char>* outside)> JoinComponents;

  /// Sums (voxels of the tissue, voxels in its tets, those of them that are its own) by label.
  void SumByLabel(std::map<std::int32_t, std::array<double, 3>>& sums) const;
  /// Sums the values of each key over the ranks (a key any rank gives is in the result).
  void SumByKey(std::map<std::int64_t, double>& sums) const;
  /// For each key, the entry of largest first value over the ranks (the lowest rank's of
  /// equals): a candidate and where it is.
  void BestByKey(std::map<std::int64_t, std::array<double, 4>>& best) const;

  bool Owns(double along) const { return along >= this->Lower && along < this->Upper; }
  /// Whether this rank's slab holds a voxel (a stored index).
  bool OwnsVoxel(const LabelImage& image, std::int64_t voxel) const
  {
    return this->Owns(image.Spacing[this->Axis] * image.VoxelCoordinates(voxel)[this->Axis]);
  }
};

/// What a rank without tissue does while the others refine its image (RefineMesh over ranks):
/// each collective call that refinement makes, in the same order, with nothing to add, until
/// every rank is done. The choices that shape the calls: whether the parameters ask for
/// refinement (RefinementParams::AsksForRefinement), measure the boundary distance
/// (BoundaryDistance not negative) and make the labels sound.
void RefineWithoutTissue(const RankPasses& ranks, bool refines, bool coverage, bool soundLabels);
} // namespace cbc3d

#endif
