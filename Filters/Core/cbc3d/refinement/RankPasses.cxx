#include "cbc3d/refinement/RankPasses.h"

#include "cbc3d/refinement/CoveragePasses.h"
#include "cbc3d/refinement/KeptComponents.h"
#include "cbc3d/refinement/SharedFarFaces.h"

namespace cbc3d
{
namespace
{
// MeasureFidelity's calls: the slab's counts, then the components found in the mesh.
void MeasureNothing(const RankPasses& ranks)
{
  std::map<std::int32_t, std::array<double, 3>> counts;
  ranks.SumByLabel(counts);
  std::map<std::int64_t, double> found;
  ranks.SumByKey(found);
}

// KeepComponentsAndMakeSound's pinning: the missing components' tets, then the few holders.
void PinNothing(const RankPasses& ranks)
{
  std::map<std::int64_t, std::array<double, 4>> best;
  ranks.BestByKey(best);
  std::map<std::int64_t, double> holders;
  ranks.SumByKey(holders);
}
} // namespace

// The calls of RefineMesh (Refinement.cxx) and its parts, in their order.
void RefineWithoutTissue(const RankPasses& ranks, bool refines, bool coverage, bool soundLabels)
{
  if (ranks.Any(false)) // another rank's inputs are not valid
    return;
  std::map<std::int64_t, double> labels;
  ranks.SumByKey(labels); // the tissues present
  if (ranks.Any(false)) // a tissue asked for is in no rank's slab
    return;
  const LabelImage none;
  RunComponents tissues, gaps;
  std::vector<char> outside;
  ranks.JoinComponents(none, tissues, nullptr);
  if (soundLabels)
    ranks.JoinComponents(none, gaps, &outside);
  CoverageProgress progress;
  do
  {
    for (;;) // the passes
    {
      MeasureNothing(ranks);
      if (!refines)
        break;
      BoundaryCoverage::Gaps none;
      double far = 0.0, largest = 0.0;
      if (coverage && progress.Stalled)
        ranks.SumAndMax(far, largest); // the pass's one call
      else if (coverage && CoverageGoesOn(none, progress, &ranks))
        FindFarFacesOnRanks(ranks, nullptr, {}, {}, {}, {}, {});
      if (!ranks.Any(false))
        break;
    }
    if (ranks.Any(false)) // surface ears removed
      MeasureNothing(ranks);
    PinNothing(ranks);
    for (int round = 1; soundLabels; ++round)
    {
      MeasureNothing(ranks);
      if (round == SoundLabelRounds)
        break;
      PinNothing(ranks);
      if (!ranks.Any(false))
        break;
    }
    if (!soundLabels)
      MeasureNothing(ranks);
  } while (ranks.Any(false)); // another round for edge limits
  ranks.Any(false);             // any tets kept
}
} // namespace cbc3d
