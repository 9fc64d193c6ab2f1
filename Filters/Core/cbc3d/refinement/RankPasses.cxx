#include "cbc3d/refinement/RankPasses.h"

#include "cbc3d/refinement/CoveragePasses.h"
#include "cbc3d/refinement/KeptComponents.h"
#include "cbc3d/refinement/SharedFarFaces.h"

#include <algorithm>

namespace cbc3d
{
namespace
{
// Every rank's rows (a key, then N values), in rank order.
template <typename Key, std::size_t N>
std::vector<std::pair<Key, std::array<double, N>>> GatherRows(
  const RankPasses& ranks, const std::map<Key, std::array<double, N>>& rows)
{
  std::vector<double> mine;
  mine.reserve((N + 1) * rows.size());
  for (const auto& [key, values] : rows)
  {
    mine.push_back(double(key)); // labels and component numbers stay far below 2^53
    mine.insert(mine.end(), values.begin(), values.end());
  }
  const std::vector<double> all = ranks.AllValues(mine);
  std::vector<std::pair<Key, std::array<double, N>>> gathered(all.size() / (N + 1));
  for (std::size_t r = 0; r < gathered.size(); ++r)
  {
    gathered[r].first = Key(all[(N + 1) * r]);
    std::copy_n(all.begin() + (N + 1) * r + 1, N, gathered[r].second.begin());
  }
  return gathered;
}

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

void RankPasses::SumByLabel(std::map<std::int32_t, std::array<double, 3>>& sums) const
{
  const auto rows = GatherRows(*this, sums);
  sums.clear();
  for (const auto& [label, values] : rows)
    for (int k = 0; k < 3; ++k)
      sums[label][k] += values[k];
}

void RankPasses::SumByKey(std::map<std::int64_t, double>& sums) const
{
  std::map<std::int64_t, std::array<double, 1>> rows;
  for (const auto& [key, value] : sums)
    rows[key] = { value };
  sums.clear();
  for (const auto& [key, values] : GatherRows(*this, rows))
    sums[key] += values[0];
}

void RankPasses::BestByKey(std::map<std::int64_t, std::array<double, 4>>& best) const
{
  const auto rows = GatherRows(*this, best);
  best.clear();
  for (const auto& [key, row] : rows) // in rank order: the first of equals stays
  {
    const auto found = best.find(key);
    if (found == best.end() || row[0] > found->second[0])
      best[key] = row;
  }
}

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
