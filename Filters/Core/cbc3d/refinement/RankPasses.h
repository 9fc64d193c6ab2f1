#ifndef cbc3d_RankPasses_h
#define cbc3d_RankPasses_h

#include <array>
#include <cstdint>
#include <functional>
#include <map>

namespace cbc3d
{
/// How the refinement passes on one rank's piece of an image take the whole image's decisions
/// (vtkCBC3DMesher over MPI ranks). Each tissue's voxel fidelity counts the voxels and tets of
/// this rank's slab alone and is summed over the ranks; so is the boundary-distance progress;
/// and the passes, and the rounds for edge limits, end on every rank together. Each function is
/// a collective call: every rank calls it as often, in the same order.
struct RankPasses
{
  int Axis = 2;       // the image axis across the slabs
  double Lower = 0.0; // this rank's slab: mm along Axis from voxel 0 of the piece, [Lower, Upper)
  double Upper = 0.0;
  /// Sums (voxels of the tissue, voxels in its tets, those of them that are its own) by label.
  std::function<void(std::map<std::int32_t, std::array<double, 3>>&)> SumByLabel;
  /// The sum of `sum` and the largest `largest` over the ranks.
  std::function<void(double& sum, double& largest)> SumAndMax;
  /// Whether any rank says yes.
  std::function<bool(bool)> Any;

  bool Owns(double along) const { return along >= this->Lower && along < this->Upper; }
};
} // namespace cbc3d

#endif
