#ifndef cbc3d_TetBudget_h
#define cbc3d_TetBudget_h

#include "cbc3d/lattice/RedGreenMesh.h"
#include "cbc3d/refinement/LabelledMesh.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace cbc3d
{
/// Refinement within a number of tissue tets (RefinementParams::MaximumTets). Each pass keeps
/// the splits that fit what is left of the budget, those that gain the most fidelity first. A
/// split's cost cannot be told from the leaf alone (the red-green closure may split its
/// neighbours, and theirs), so candidate sets are tried on a copy of the hierarchy.
class TetBudget
{
public:
  /// `target`: the tissue tets the passes aim at, a little under the user's maximum, since
  /// making the labels sound afterwards moves the count.
  explicit TetBudget(std::int64_t target)
    : Target(target)
  {
  }

  /// Keeps, of the marked leaves (`marked`, per red; MarkedForEdgeLimit first) and the edges
  /// to bisect, as many as fit the budget; returns the leaves kept. False in `fits` when none
  /// fits: the budget is spent.
  std::size_t Keep(const LabelImage& image, const LabelledMesh& mesh, const RedGreenMesh& hierarchy,
    std::vector<char>& marked, std::vector<std::pair<PointId, PointId>>& bisect, int threads, bool& fits) const;

private:
  std::int64_t Target;
};
} // namespace cbc3d

#endif
