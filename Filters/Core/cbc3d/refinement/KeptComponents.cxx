#include "cbc3d/refinement/KeptComponents.h"

#include "cbc3d/soundlabels/SoundLabels.h"

#include <algorithm>

namespace cbc3d
{
namespace
{
// Rounds of making the labels sound, each after giving lost components their tets back.
constexpr int SoundLabelRounds = 3;

// A component still missing (at the minimum edge length) gets the tet holding most of it
// (counted in `restored`); that tet, and the tets of a component that only one or two tets
// stand for, are pinned to its label (tet -> label) so that making the labels sound does not
// lose the component.
std::map<std::int64_t, std::int32_t> PinComponents(const LabelImage& image,
  const TissueComponents& components, int minimumVoxels, LabelledMesh& mesh,
  const std::vector<char>& componentInMesh, std::int64_t& restored)
{
  constexpr std::size_t FewTets = 2;
  // A component in the mesh needs only whether FewTets tets or fewer hold it (its first tets,
  // up to one more than that); a missing one needs every holder's count, but missing ones are
  // rare.
  const std::size_t count = components.Label.size();
  std::vector<std::vector<std::int32_t>> fewHolders(count);
  std::map<std::int32_t, std::map<std::int32_t, std::int64_t>> missing; // component -> tet -> voxels
  for (const TissueComponents::Run& run : components.Runs)
  {
    const std::int32_t component = run.Component;
    auto& holders = fewHolders[component];
    if (IsSmall(components, component, minimumVoxels) || (componentInMesh[component] && holders.size() > FewTets))
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
        ++missing[component][owner];
      }
      else if (mesh.Labels[owner] == components.Label[component] && holders.size() <= FewTets &&
        std::find(holders.begin(), holders.end(), owner) == holders.end())
      {
        holders.push_back(owner);
      }
    }
  }
  std::map<std::int64_t, std::int32_t> pinned;
  for (std::size_t component = 0; component < count; ++component)
  {
    const std::int32_t label = components.Label[component];
    const auto found = missing.find(std::int32_t(component));
    if (found != missing.end())
    {
      const auto& tets = found->second;
      const auto best = std::max_element(tets.begin(), tets.end(),
        [](const auto& a, const auto& b) { return a.second < b.second; }); // first of equals wins
      restored += mesh.Labels[best->first] != label;
      mesh.Labels[best->first] = label;
      pinned[best->first] = label;
    }
    else if (fewHolders[component].size() <= FewTets)
    {
      for (const std::int32_t tet : fewHolders[component])
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
  const TissueComponents& components, const RefinementParams& params,
  const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<std::int64_t, 4>>& across,
  LabelledMesh& mesh, std::vector<char>& componentInMesh, std::int64_t& relabelled)
{
  std::int64_t restored = 0;
  std::map<std::int64_t, std::int32_t> pinned =
    PinComponents(image, components, params.MinimumComponentVoxels, mesh, componentInMesh, restored);
  const auto measure = [&] {
    return MeasureFidelity(
      image, components, params.MinimumComponentVoxels, mesh, params.NumberOfThreads, componentInMesh);
  };
  if (!params.SoundLabels)
  {
    return measure();
  }
  for (int round = 1;; ++round)
  {
    relabelled += MakeLabelsSound(image, components, params.MinimumComponentVoxels,
      points, mesh.Tets, across, mesh.Counts, mesh.VoxelOwner, pinned, NoLabel,
      mesh.Labels, params.NumberOfThreads).Relabelled;
    std::map<std::int32_t, TissueFidelity> fidelity = measure();
    if (round == SoundLabelRounds)
    {
      return fidelity;
    }
    // Pinning only tets the repair already respected, and giving back none, would change nothing.
    const std::size_t before = pinned.size();
    restored = 0;
    const auto lost =
      PinComponents(image, components, params.MinimumComponentVoxels, mesh, componentInMesh, restored);
    pinned.insert(lost.begin(), lost.end());
    if (pinned.size() == before && restored == 0)
    {
      return fidelity;
    }
  }
}
} // namespace cbc3d
