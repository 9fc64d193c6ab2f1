#include "cbc3d/refinement/KeptComponents.h"

#include "cbc3d/base/TetGeometry.h"
#include "cbc3d/soundlabels/SoundLabels.h"

#include <algorithm>
#include <set>

namespace cbc3d
{
namespace
{
// A component in the mesh that this many tets or fewer stand for has them pinned.
constexpr std::size_t FewTets = 2;

// What the tets hold of the components that PinComponents looks at. Over ranks, a component is
// the whole image's (its WholeId), and a tet counts where this rank owns it.
struct Holdings
{
  // Missing component -> tet -> its voxel centres the tet owns.
  std::map<std::int64_t, std::map<std::int32_t, std::int64_t>> Missing;
  // Per component in the mesh: its first tets of its label (up to FewTets + 1 that count).
  std::vector<std::vector<std::int32_t>> Holders;
  std::vector<std::size_t> Counted; // per component: its holders that count
};

Eigen::Vector3d Centre(const std::vector<Eigen::Vector3d>& points, const Tet& tet)
{
  return Centroid(points[tet[0]], points[tet[1]], points[tet[2]], points[tet[3]]);
}

Holdings FindHoldings(const TissueComponents& components, int minimumVoxels,
  const LabelledMesh& mesh, const std::vector<char>& componentInMesh, const std::vector<char>& counts)
{
  const bool whole = !components.WholeId.empty();
  Holdings found;
  found.Holders.resize(components.Label.size());
  found.Counted.assign(components.Label.size(), 0);
  for (const TissueComponents::Run& run : components.Runs)
  {
    const std::int32_t component = run.Component;
    auto& holders = found.Holders[component];
    if (IsSmall(components, component, minimumVoxels) ||
      (componentInMesh[component] && found.Counted[component] > FewTets))
    {
      continue; // nothing this run holds can change the outcome
    }
    for (std::int64_t v = run.First; v <= run.Last; ++v)
    {
      const std::int32_t owner = mesh.OwnerOf(v);
      if (owner < 0)
      {
        continue;
      }
      if (!componentInMesh[component])
      {
        ++found.Missing[whole ? components.WholeId[component] : component][owner];
      }
      else if (mesh.Labels[owner] == components.Label[component] && found.Counted[component] <= FewTets &&
        std::find(holders.begin(), holders.end(), owner) == holders.end())
      {
        holders.push_back(owner);
        found.Counted[component] += counts.empty() || counts[owner];
      }
    }
  }
  return found;
}

// Over ranks: the tet that holds most of each missing component over the whole image (a
// rank's own tets compete; the lowest rank's of equals wins), as this rank's tet of the same
// count and centre; and the components in the mesh that few tets stand for over the whole image.
void DecideAcrossRanks(const TissueComponents& components, const RankPasses& ranks,
  const std::vector<Eigen::Vector3d>& points, const LabelledMesh& mesh, const std::vector<char>& owned,
  Holdings& found)
{
  std::map<std::int64_t, std::array<double, 4>> best;
  for (const auto& [component, tets] : found.Missing)
  {
    for (const auto& [tet, voxels] : tets)
    {
      auto entry = best.try_emplace(component, std::array<double, 4>{ -1.0, 0, 0, 0 }).first;
      if (owned[tet] && double(voxels) > entry->second[0])
      {
        const Eigen::Vector3d centre = Centre(points, mesh.Tets[tet]);
        entry->second = { double(voxels), centre[0], centre[1], centre[2] };
      }
    }
  }
  ranks.BestByKey(best);
  for (auto& [component, tets] : found.Missing)
  {
    const std::array<double, 4>& winner = best[component];
    const Eigen::Vector3d at(winner[1], winner[2], winner[3]);
    std::map<std::int32_t, std::int64_t> kept;
    for (const auto& [tet, voxels] : tets)
    {
      if (double(voxels) == winner[0] && (Centre(points, mesh.Tets[tet]) - at).norm() < 1e-6 * (1.0 + at.norm()))
        kept[tet] = voxels;
    }
    tets.swap(kept);
  }
  std::map<std::int64_t, double> counted;
  for (std::size_t c = 0; c < found.Holders.size(); ++c)
    if (!found.Holders[c].empty())
      counted[components.WholeId[c]] += double(found.Counted[c]);
  ranks.SumByKey(counted);
  for (std::size_t c = 0; c < found.Holders.size(); ++c)
    if (!found.Holders[c].empty() && counted[components.WholeId[c]] > double(FewTets))
      found.Holders[c].clear();
}

// A component still missing (at the minimum edge length) gets the tet holding most of it
// (counted in `restored`); that tet, and the tets of a component that only one or two tets
// stand for, are pinned to its label (tet -> label) so that making the labels sound does not
// lose the component.
std::map<std::int64_t, std::int32_t> PinComponents(const LabelImage& image,
  const TissueComponents& components, const RefinementParams& params, const std::vector<Eigen::Vector3d>& points,
  LabelledMesh& mesh, const std::vector<char>& componentInMesh, std::int64_t& restored)
{
  // A component in the mesh needs only whether FewTets tets or fewer hold it (its first tets,
  // up to one more than that); a missing one needs every holder's count, but missing ones are
  // rare.
  const RankPasses* ranks = params.Ranks.get();
  const std::vector<char> owned = ranks ? RankOwnedTets(image, points, mesh.Tets, *ranks) : std::vector<char>();
  Holdings found = FindHoldings(components, params.MinimumComponentVoxels, mesh, componentInMesh, owned);
  if (ranks)
  {
    DecideAcrossRanks(components, *ranks, points, mesh, owned, found);
  }
  std::map<std::int64_t, std::int32_t> pinned;
  std::set<std::int64_t> restoredWhole; // over ranks: the pieces of a component share one tet
  for (std::size_t component = 0; component < components.Label.size(); ++component)
  {
    const std::int32_t label = components.Label[component];
    const std::int64_t key = ranks ? components.WholeId[component] : std::int64_t(component);
    const auto missing = found.Missing.find(key);
    if (!componentInMesh[component] && missing != found.Missing.end())
    {
      const auto& tets = missing->second;
      if (tets.empty() || (ranks && !restoredWhole.insert(key).second))
        continue; // no tet of this rank holds it, or another piece of it has its tet
      const auto best = std::max_element(tets.begin(), tets.end(),
        [](const auto& a, const auto& b) { return a.second < b.second; }); // first of equals wins
      restored += mesh.Labels[best->first] != label;
      mesh.Labels[best->first] = label;
      pinned[best->first] = label;
    }
    else if (componentInMesh[component] && found.Holders[component].size() > 0 &&
      (ranks || found.Holders[component].size() <= FewTets))
    {
      for (const std::int32_t tet : found.Holders[component])
        pinned[tet] = label;
    }
  }
  return pinned;
}
} // namespace

// A component still missing gets the tet holding most of it (PinComponents); then, with
// SoundLabels: no hinge, no non-manifold surface, no piece the image does not have, and a
// component the repair lost gets its tet back, pinned, and the repair runs again around it.
// The labels always end as the repair left them: a component it still loses in the last round
// stays lost (and the fidelity says so), since a sound mesh comes first.
// Returns the fidelity of the labels as they end.
std::map<std::int32_t, TissueFidelity> KeepComponentsAndMakeSound(const LabelImage& image,
  const TissueComponents& components, const ImageRegions* regions, const RefinementParams& params,
  const std::vector<Eigen::Vector3d>& points, const std::vector<TetNeighbours>& across,
  LabelledMesh& mesh, std::vector<char>& componentInMesh, std::int64_t& relabelled)
{
  std::int64_t restored = 0;
  std::map<std::int64_t, std::int32_t> pinned =
    PinComponents(image, components, params, points, mesh, componentInMesh, restored);
  const auto measure = [&] {
    return MeasureFidelity(image, components, params.MinimumComponentVoxels, mesh, params.NumberOfThreads,
      componentInMesh, params.Ranks.get(), &points);
  };
  if (!params.SoundLabels)
  {
    return measure();
  }
  for (int round = 1;; ++round)
  {
    relabelled += MakeLabelsSound(image, *regions, points, mesh.Tets, across, mesh.Counts, mesh.VoxelOwner, pinned,
      NoLabel, mesh.Labels, params.NumberOfThreads).Relabelled;
    std::map<std::int32_t, TissueFidelity> fidelity = measure();
    if (round == SoundLabelRounds)
    {
      return fidelity;
    }
    // Pinning only tets the repair already respected, and giving back none, would change nothing.
    const std::size_t before = pinned.size();
    restored = 0;
    const auto lost = PinComponents(image, components, params, points, mesh, componentInMesh, restored);
    pinned.insert(lost.begin(), lost.end());
    const bool unchanged = pinned.size() == before && restored == 0;
    if (params.Ranks ? !params.Ranks->Any(!unchanged) : unchanged)
    {
      return fidelity;
    }
  }
}
} // namespace cbc3d
