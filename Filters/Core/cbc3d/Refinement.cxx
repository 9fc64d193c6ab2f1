#include "cbc3d/Refinement.h"

#include "cbc3d/BCCLattice.h"

#include "cbc3d/BoundaryCoverage.h"
#include "cbc3d/ManifoldRepair.h"
#include "cbc3d/MeshFaces.h"
#include "cbc3d/Parallel.h"
#include "cbc3d/RedGreenMesh.h"
#include "cbc3d/SoundLabels.h"
#include "cbc3d/SurfaceEars.h"
#include "cbc3d/TetVoxelSampler.h"
#include "cbc3d/TissueComponents.h"

#include <algorithm>
#include <atomic>
#include <functional>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

namespace cbc3d
{
namespace
{
// A tet that holds no sample at all (outside the image) has no label.
constexpr std::int32_t NoLabel = std::numeric_limits<std::int32_t>::min();

// Rounds of making the labels sound, each after giving lost components their tets back.
constexpr int SoundLabelRounds = 3;

// Bytes per tet at peak: the hierarchy, the final tets, their samples and the VTK output.
constexpr double BytesPerTet = 400.0;

// One pass's view of the conforming mesh: tets, their red leaves, samples and labels.
struct LabelledMesh
{
  std::vector<Tet> Tets;
  std::vector<std::int64_t> Source;
  std::vector<LabelCounts> Counts;
  std::vector<char> HoldsVoxelCentres; // counts are whole voxels (else sub-samples)
  std::vector<std::int32_t> Labels;

  // The tet owning each voxel centre, as an owner id (-1: none), and the tet of each id. Ids
  // outlive passes: a tet that a pass leaves as it was keeps its id and its voxels' entries,
  // so only the voxels of new tets are written again.
  VoxelOwners VoxelOwner;
  std::vector<std::int32_t> OwnerTet;
  std::int32_t OwnerOf(std::int64_t voxel) const
  {
    const std::int32_t id = this->VoxelOwner[voxel];
    return id < 0 ? -1 : this->OwnerTet[id];
  }

  // What the last pass sampled, per red: its split mask as a leaf (RedGreenMesh::NotLeaf if
  // none), its first tet and that tet's owner id. A leaf with the same mask makes the same
  // tets, whose samples are taken over.
  std::vector<std::uint8_t> LeafMask;
  std::vector<std::int64_t> FirstTet;
  std::vector<std::int32_t> FirstOwner;
};

// Where each tet's samples come from: the last pass's tet (-1: sampled now), and its owner id.
// New tets get new ids, after `nextOwner`.
void MatchLastPass(const LabelledMesh& mesh, const std::vector<std::uint8_t>& masks, std::int32_t nextOwner,
  std::vector<std::int64_t>& takenFrom, std::vector<std::int32_t>& owner, std::vector<std::int64_t>& firstTet,
  std::vector<std::int32_t>& firstOwner)
{
  const std::int64_t count = static_cast<std::int64_t>(mesh.Tets.size());
  takenFrom.assign(count, -1);
  owner.assign(count, -1);
  firstTet.assign(masks.size(), -1);
  firstOwner.assign(masks.size(), -1);
  for (std::int64_t t = 0; t < count; ++t)
  {
    const std::int64_t red = mesh.Source[t];
    const bool first = firstTet[red] < 0;
    if (first)
    {
      firstTet[red] = t;
    }
    const std::int64_t k = t - firstTet[red];
    if (static_cast<std::size_t>(red) < mesh.LeafMask.size() && mesh.LeafMask[red] == masks[red])
    {
      takenFrom[t] = mesh.FirstTet[red] + k;
      owner[t] = mesh.FirstOwner[red] + static_cast<std::int32_t>(k);
    }
    else
    {
      owner[t] = nextOwner++;
    }
    if (first)
    {
      firstOwner[red] = owner[t];
    }
  }
}

// Returns false when `keepGoing` (polled from thread 0) asked to stop.
bool SampleAll(const LabelImage& image, const RedGreenMesh& hierarchy, int threads,
  LabelledMesh& mesh, const std::function<bool()>& keepGoing)
{
  std::vector<std::uint8_t> masks;
  if (!hierarchy.BuildConforming(mesh.Tets, mesh.Source, keepGoing, &masks, threads))
  {
    return false;
  }
  const std::int64_t count = static_cast<std::int64_t>(mesh.Tets.size());
  const std::int64_t ids = static_cast<std::int64_t>(mesh.OwnerTet.size());
  if (mesh.VoxelOwner.size() != image.Labels.size() || ids + count > std::numeric_limits<std::int32_t>::max())
  {
    AssignInParallel(mesh.VoxelOwner, image.Labels.size(), -1, threads); // the first pass, or ids running out
    mesh.OwnerTet.clear();
    mesh.LeafMask.clear();
  }
  std::vector<std::int64_t> takenFrom, firstTet;
  std::vector<std::int32_t> owner, firstOwner;
  MatchLastPass(mesh, masks, static_cast<std::int32_t>(mesh.OwnerTet.size()), takenFrom, owner, firstTet, firstOwner);
  std::vector<LabelCounts> lastCounts = std::move(mesh.Counts);
  std::vector<char> lastHolds = std::move(mesh.HoldsVoxelCentres);
  mesh.Counts.assign(count, LabelCounts());
  mesh.HoldsVoxelCentres.assign(count, 0);
  mesh.Labels.assign(count, NoLabel);
  std::atomic<bool> stop(false);
  const auto& points = hierarchy.Points();
  auto sample = [&](std::int64_t t) {
    if (takenFrom[t] >= 0)
    {
      mesh.Counts[t] = std::move(lastCounts[takenFrom[t]]);
      mesh.HoldsVoxelCentres[t] = lastHolds[takenFrom[t]];
    }
    else
    {
      const Tet& tet = mesh.Tets[t];
      mesh.HoldsVoxelCentres[t] = 1 ==
        SampleTetLabels(image, { points[tet[0]], points[tet[1]], points[tet[2]], points[tet[3]] },
          mesh.Counts[t], owner[t], mesh.VoxelOwner.data());
    }
    std::int32_t label = NoLabel;
    mesh.Counts[t].Majority(image, label);
    mesh.Labels[t] = label;
  };
  RegionErrors errors; // a tet's label counts grow
#pragma omp parallel for schedule(dynamic, 256) num_threads(ThreadCount(threads))
  for (std::int64_t t = 0; t < count; ++t)
  {
    if (stop.load(std::memory_order_relaxed) || errors.Failed())
    {
      continue;
    }
    if (ThreadId() == 0 && t % 4096 == 0 && !keepGoing())
    {
      stop.store(true);
    }
    errors.Run([&] { sample(t); });
  }
  errors.Rethrow();
  if (stop.load())
  {
    mesh.VoxelOwner.clear(); // the owners are a mix of two passes: a next pass starts afresh
    return false;
  }
  // Ids of tets gone (their voxels all taken by new tets) lead nowhere.
  mesh.OwnerTet.assign(owner.empty() ? 0 : static_cast<std::size_t>(*std::max_element(owner.begin(), owner.end())) + 1, -1);
  for (std::int64_t t = 0; t < count; ++t)
  {
    mesh.OwnerTet[owner[t]] = static_cast<std::int32_t>(t);
  }
  mesh.LeafMask = std::move(masks);
  mesh.FirstTet = std::move(firstTet);
  mesh.FirstOwner = std::move(firstOwner);
  // Thread 0 may have had no turn to poll (a small mesh, a busy machine): ask once more.
  return keepGoing();
}

// After the passes: every voxel's owner as its tet, and each tet its own id.
void ResolveOwners(LabelledMesh& mesh, int threads)
{
  const std::int64_t voxels = static_cast<std::int64_t>(mesh.VoxelOwner.size());
#pragma omp parallel for schedule(static) num_threads(ThreadCount(threads))
  for (std::int64_t v = 0; v < voxels; ++v)
  {
    mesh.VoxelOwner[v] = mesh.OwnerOf(v);
  }
  mesh.OwnerTet.resize(mesh.Tets.size());
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    mesh.OwnerTet[t] = static_cast<std::int32_t>(t);
  }
}

// Per tissue label, the voxel centres in its tets and those of them of its label (whole
// numbers of sample weights, summed exactly: the same in any order, so in parallel).
void CountTissueVoxelsInTets(const LabelImage& image, const LabelledMesh& mesh, int threads,
  std::map<std::int32_t, double>& inTets, std::map<std::int32_t, double>& shared)
{
  std::map<std::int32_t, std::pair<std::int64_t, std::int64_t>> counts;
  const std::int64_t count = static_cast<std::int64_t>(mesh.Tets.size());
  RegionErrors errors; // the maps grow
#pragma omp parallel num_threads(ThreadCount(threads))
  {
    std::map<std::int32_t, std::pair<std::int64_t, std::int64_t>> local;
#pragma omp for schedule(static) nowait
    for (std::int64_t t = 0; t < count; ++t)
    {
      // Only voxel centres count: each belongs to one tet. Sub-sampled tets hold none.
      const std::int32_t label = mesh.Labels[t];
      if (mesh.HoldsVoxelCentres[t] && label != NoLabel && image.IsTissue(label))
      {
        errors.Run([&] {
          auto& entry = local[label];
          entry.first += mesh.Counts[t].Total();
          entry.second += mesh.Counts[t].Of(label);
        });
      }
    }
#pragma omp critical
    errors.Run([&] {
      for (const auto& [label, sums] : local)
      {
        counts[label].first += sums.first;
        counts[label].second += sums.second;
      }
    });
  }
  errors.Rethrow();
  for (const auto& [label, sums] : counts)
  {
    inTets[label] = double(sums.first);
    shared[label] = double(sums.second);
  }
}

// F1 and F2 of every tissue, and its components kept in the mesh.
std::map<std::int32_t, TissueFidelity> MeasureFidelity(const LabelImage& image,
  const TissueComponents& components, int minimumVoxels, const LabelledMesh& mesh, int threads,
  std::vector<char>& componentInMesh)
{
  std::map<std::int32_t, double> inTets, shared, inImage;
  for (std::size_t c = 0; c < components.Label.size(); ++c)
  {
    inImage[components.Label[c]] += double(components.Size[c]) * double(VoxelWeight);
  }
  CountTissueVoxelsInTets(image, mesh, threads, inTets, shared);
  componentInMesh.assign(components.Label.size(), 0);
  const std::int64_t runCount = static_cast<std::int64_t>(components.Runs.size());
#pragma omp parallel for schedule(dynamic, 64) num_threads(ThreadCount(threads))
  for (std::int64_t r = 0; r < runCount; ++r)
  {
    // One voxel in a tet of its label is enough: a component found already is not looked at.
    const std::int32_t component = components.Runs[r].Component;
    char found;
#pragma omp atomic read
    found = componentInMesh[component];
    for (std::int64_t v = components.Runs[r].First; !found && v <= components.Runs[r].Last; ++v)
    {
      const std::int32_t owner = mesh.OwnerOf(v);
      if (owner >= 0 && mesh.Labels[owner] == components.Label[component])
      {
#pragma omp atomic write
        componentInMesh[component] = 1;
        found = 1;
      }
    }
  }
  std::map<std::int32_t, TissueFidelity> result;
  for (const auto& [label, voxels] : inImage)
  {
    TissueFidelity& f = result[label];
    f.Label = label;
    f.F1 = inTets[label] > 0 ? shared[label] / inTets[label] : 0.0;
    f.F2 = voxels > 0 ? shared[label] / voxels : 0.0;
  }
  for (std::size_t c = 0; c < components.Label.size(); ++c)
  {
    if (components.Size[c] >= minimumVoxels)
    {
      TissueFidelity& f = result[components.Label[c]];
      ++f.Components;
      f.ComponentsInMesh += componentInMesh[c];
    }
  }
  return result;
}

bool IsSmall(const TissueComponents& components, std::int32_t component, int minimumVoxels)
{
  return components.Size[component] < minimumVoxels;
}

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

// The image, the mesh to refine and the parameters' ranges, or an error naming what is wrong.
Status ValidateInputs(const LabelImage& image, const TetMesh& lattice, const RefinementParams& params)
{
  const Status valid = ValidateLabelImage(image);
  if (!valid.IsOk())
  {
    return valid;
  }
  if (!(params.Fidelity >= 0.0 && params.Fidelity <= 1.0))
  {
    return Status::Error("the fidelity must be a number from 0 to 1");
  }
  if (!(params.MinimumEdgeLength >= 0.0) || !std::isfinite(params.MinimumEdgeLength))
  {
    return Status::Error("the minimum edge length must be 0 (automatic) or a positive length in mm");
  }
  if (!std::isfinite(params.BoundaryDistance))
  {
    return Status::Error("the boundary distance must be 0 (automatic), negative (none) or a "
                         "length in mm");
  }
  if (lattice.Tets.empty())
  {
    return Status::Error("the mesh to refine has no tets");
  }
  return Status::Ok();
}

// Which leaves to split red for fidelity: those whose tets cross the boundary of a tissue below
// the target, and those holding a tissue component that no tet of its tissue represents yet.
std::vector<char> MarkForFidelity(const LabelImage& image, const TissueComponents& components,
  const RefinementParams& params, const LabelledMesh& mesh,
  const std::map<std::int32_t, TissueFidelity>& fidelity, const std::vector<char>& componentInMesh,
  std::size_t leaves)
{
  auto isFailing = [&](std::int32_t label) {
    const auto found = fidelity.find(label);
    return found != fidelity.end() &&
      (found->second.F1 < params.Fidelity || found->second.F2 < params.Fidelity);
  };
  std::vector<char> marked(leaves, 0);
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const auto& counts = mesh.Counts[t].Counts;
    if (counts.size() < 2)
    {
      continue;
    }
    for (const auto& entry : counts)
    {
      if (isFailing(entry.first))
      {
        marked[mesh.Source[t]] = 1;
        break;
      }
    }
  }
  // The tets holding a component that is missing from the mesh (rare: most runs are skipped).
  for (const TissueComponents::Run& run : components.Runs)
  {
    if (componentInMesh[run.Component] || IsSmall(components, run.Component, params.MinimumComponentVoxels))
    {
      continue;
    }
    for (std::int64_t v = run.First; v <= run.Last; ++v)
    {
      const std::int32_t owner = mesh.OwnerOf(v);
      if (owner >= 0)
      {
        marked[mesh.Source[owner]] = 1;
      }
    }
  }
  return marked;
}

// How refining for the boundary distance stands between passes: the gaps the last pass found
// (FarVoxels -1: none looked for yet), and whether a pass stopped gaining.
struct CoverageProgress
{
  double LargestGap = 0.0;
  std::int64_t FarVoxels = -1;
  bool Stalled = false; // the later passes refine for fidelity alone
};

// Where the surface would stay far from the image boundary (more than `distance`): a new
// surface vertex on the longest edge of the face nearest to a far boundary voxel (a green split
// of the tets around the edge, into `bisect`), or a red split of the leaf where that edge is not
// one of the leaf's own; and a red split of the tets with a vertex that cannot reach the
// boundary. Returns whether any split was wanted (at the depth limit or not); none once a pass
// brings neither the farthest voxel nearer nor fewer voxels far (`progress` then stalls).
bool MarkForCoverage(const BoundaryCoverage& coverage, double distance, const RedGreenMesh& hierarchy,
  const LabelledMesh& mesh, double minimumEdge, CoverageProgress& progress, std::vector<char>& marked,
  std::vector<std::pair<PointId, PointId>>& bisect)
{
  const auto& x = hierarchy.Points();
  const BoundaryCoverage::Gaps gaps = coverage.Find(x, mesh.Tets, mesh.Labels, distance);
  BoundaryCoverage::Gaps before;
  before.LargestGap = progress.LargestGap;
  before.FarVoxels = progress.FarVoxels;
  progress.LargestGap = gaps.LargestGap;
  progress.FarVoxels = gaps.FarVoxels;
  if (before.FarVoxels >= 0 && !gaps.NarrowerThan(before))
  {
    progress.Stalled = true;
    return false;
  }
  const bool wanted = !gaps.FarFaces.empty() || !gaps.StrandedTets.empty();
  for (const std::int64_t t : gaps.StrandedTets)
  {
    marked[mesh.Source[t]] = 1;
  }
  for (const BoundaryCoverage::Face& face : gaps.FarFaces)
  {
    int longest = 0;
    auto length = [&](int e) { return (x[face.Points[e]] - x[face.Points[(e + 1) % 3]]).norm(); };
    for (int e = 1; e < 3; ++e)
    {
      longest = length(e) > length(longest) ? e : longest;
    }
    const PointId a = face.Points[longest], b = face.Points[(longest + 1) % 3];
    const std::int64_t red = mesh.Source[face.Tet];
    const Tet& corners = hierarchy.Reds()[red].Points;
    const bool leafEdge = std::count(corners.begin(), corners.end(), a) > 0 &&
      std::count(corners.begin(), corners.end(), b) > 0;
    if (!leafEdge)
    {
      marked[red] = 1;
    }
    else if (length(longest) / 2.0 >= minimumEdge * (1.0 - 1e-9))
    {
      bisect.emplace_back(a, b);
    }
  }
  return wanted;
}

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

// The tissue tets, their points renumbered, and each one's red level.
void KeepTissueTets(const LabelImage& image, const RedGreenMesh& hierarchy, const LabelledMesh& mesh,
  TetMesh& out, RefinementResult& result)
{
  std::vector<PointId> newId(hierarchy.Points().size(), -1);
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const std::int32_t label = mesh.Labels[t];
    if (label == NoLabel || !image.IsTissue(label))
    {
      continue;
    }
    Tet tet;
    for (int v = 0; v < 4; ++v)
    {
      PointId& id = newId[mesh.Tets[t][v]];
      if (id < 0)
      {
        id = static_cast<PointId>(out.Points.size());
        out.Points.push_back(hierarchy.Points()[mesh.Tets[t][v]]);
      }
      tet[v] = id;
    }
    out.Tets.push_back(tet);
    out.Labels.push_back(label);
    const int level = hierarchy.Reds()[mesh.Source[t]].Level;
    result.Levels.push_back(static_cast<std::uint8_t>(level));
    result.DeepestLevel = std::max(result.DeepestLevel, level);
  }
}

// The check of the boundary distance (0: 3/8 of the lattice's longest edge, recorded in
// `result`); none where the bound is negative.
std::unique_ptr<BoundaryCoverage> MakeCoverage(const LabelImage& image, const TissueComponents& components,
  const RefinementParams& params, const RedGreenMesh& hierarchy, RefinementResult& result)
{
  if (params.BoundaryDistance < 0.0)
  {
    return nullptr;
  }
  double longest = 0.0;
  for (std::size_t red = 0; red < hierarchy.Reds().size(); ++red)
  {
    longest = std::max(longest, hierarchy.LongestEdge(red));
  }
  result.BoundaryDistance = params.BoundaryDistance > 0.0 ? params.BoundaryDistance : 0.375 * longest;
  // Deformation moves a vertex by about an element size: the lattice's shortest edge.
  return std::make_unique<BoundaryCoverage>(image, components, params.MinimumComponentVoxels,
    hierarchy.ShortestEdge(0), params.NumberOfThreads);
}

// Why the passes ended. The words come last (StopReason), when the fidelity after the sound
// labels is known as well.
struct PassesEnd
{
  enum Kind
  {
    NoRefinementAsked, // fidelity 0
    TargetsReached,    // no tissue's fidelity (nor the boundary distance) wants a split
    AtMinimumEdge,     // splits are wanted, at tets that may not be split
    MemoryLimit        // the splits would pass it
  };
  Kind End = TargetsReached;
  std::int64_t ExpectedTets = 0; // with MemoryLimit: the tets the splits would have made
};

// How a stop reason begins when no tissue's fidelity wants a split.
const std::string ReachedFidelity = "every tissue reached the fidelity target";

// Why refinement ended, in words: how the passes ended, how refining for the boundary distance
// did (`coverage`: whether there was any), and whether making the labels sound took a tissue
// below the fidelity target after the passes had reached it (the 3 mm head's CSF and grey matter).
std::string StopReason(const PassesEnd& passes, bool coverage, const CoverageProgress& progress, bool belowTarget)
{
  std::ostringstream reason;
  switch (passes.End)
  {
    case PassesEnd::NoRefinementAsked:
      return "no refinement asked (fidelity 0)";
    case PassesEnd::AtMinimumEdge:
      return "the tets left to refine are at the minimum edge length";
    case PassesEnd::MemoryLimit:
      reason << "stopped before exceeding the memory limit (about " << passes.ExpectedTets << " tets)";
      return reason.str();
    case PassesEnd::TargetsReached:
      break;
  }
  reason << ReachedFidelity;
  if (coverage)
    reason << (progress.Stalled ? ", and refining for the boundary distance stopped gaining" : " and the boundary distance");
  if (belowTarget)
    reason << "; making the labels sound took some below it";
  return reason.str();
}

// Unmarks the marked leaves at the depth limit (a split would make edges shorter than
// `minimumEdge`) and counts the rest; `anyWanted` becomes true where any leaf was marked.
std::size_t KeepSplittable(const RedGreenMesh& hierarchy, double minimumEdge, std::vector<char>& marked,
  bool& anyWanted)
{
  std::size_t splits = 0;
  for (std::size_t red = 0; red < marked.size(); ++red)
  {
    if (!marked[red])
    {
      continue;
    }
    anyWanted = true;
    marked[red] = hierarchy.ShortestEdge(red) / 2.0 >= minimumEdge * (1.0 - 1e-9);
    splits += marked[red];
  }
  return splits;
}
// How small a tet may get, and how much memory the mesh may take.
struct PassLimits
{
  double MinimumEdge;
  std::size_t MemoryBytes;
};

// Marks the reds that fidelity or coverage wants split (and that may be) and the edges coverage
// bisects, and splits them; false, with how the passes ended in `end`, when there is nothing
// left to split or the splits would pass the memory limit.
bool SplitOnePass(const LabelImage& image, const TissueComponents& components, const RefinementParams& params,
  const BoundaryCoverage* coverage, double distance, const PassLimits& limits,
  const std::map<std::int32_t, TissueFidelity>& fidelity, const std::vector<char>& componentInMesh,
  const LabelledMesh& mesh, RedGreenMesh& hierarchy, CoverageProgress& progress, PassesEnd& end)
{
  std::vector<char> marked = MarkForFidelity(image, components, params, mesh, fidelity, componentInMesh,
    hierarchy.Reds().size());
  std::vector<std::pair<PointId, PointId>> bisect;
  const bool coverageWanted = coverage && !progress.Stalled &&
    MarkForCoverage(*coverage, distance, hierarchy, mesh, limits.MinimumEdge, progress, marked, bisect);
  bool anyWanted = coverageWanted;
  const std::size_t splits = KeepSplittable(hierarchy, limits.MinimumEdge, marked, anyWanted);
  if (splits == 0 && bisect.empty())
  {
    end.End = anyWanted ? PassesEnd::AtMinimumEdge : PassesEnd::TargetsReached;
    return false;
  }
  // Each red split makes 8 tets of one; closure adds some more.
  const double expectedTets = double(mesh.Tets.size()) + 10.0 * double(splits) + 6.0 * double(bisect.size());
  if (expectedTets * BytesPerTet > double(limits.MemoryBytes))
  {
    end.End = PassesEnd::MemoryLimit;
    end.ExpectedTets = std::llround(expectedTets);
    return false;
  }
  for (std::size_t red = 0; red < marked.size(); ++red)
  {
    if (marked[red])
    {
      hierarchy.SplitRed(red);
    }
  }
  for (const auto& [a, b] : bisect)
  {
    hierarchy.SplitEdge(a, b);
  }
  return true;
}
} // namespace

Status RefineMesh(const LabelImage& image, const TetMesh& lattice, const RefinementParams& params,
  TetMesh& out, RefinementResult& result, const Progress& progress)
{
  out = TetMesh();
  result = RefinementResult();
  const Status valid = ValidateInputs(image, lattice, params);
  if (!valid.IsOk())
  {
    return valid;
  }
  const double minimumEdge = params.MinimumEdgeLength > 0.0 ? params.MinimumEdgeLength
                                                            : std::cbrt(image.Spacing.prod());
  const std::size_t memoryLimit =
    params.MemoryLimitBytes > 0 ? params.MemoryLimitBytes : PhysicalMemoryBytes() / 2;

  const TissueComponents components = FindTissueComponents(image);
  // Sound labels need background on both sides of a thin sheet of tissue to thicken it into.
  TetMesh ringed = lattice;
  if (params.SoundLabels)
    AddBackgroundRing(image, ringed);
  RedGreenMesh hierarchy(ringed);
  const std::unique_ptr<BoundaryCoverage> coverage = MakeCoverage(image, components, params, hierarchy, result);
  LabelledMesh mesh;
  std::map<std::int32_t, TissueFidelity> fidelity;
  std::vector<char> componentInMesh;
  CoverageProgress coverageProgress;
  PassesEnd passesEnd;
  const int expectedPasses = 2 + static_cast<int>(std::ceil(std::log2(
    std::max(1.0, hierarchy.ShortestEdge(0) / minimumEdge))));

  for (int pass = 0;; ++pass)
  {
    const double done = std::min(0.95, double(pass + 1) / double(expectedPasses + 1));
    const std::function<bool()> keepGoing = [&] { return KeepGoing(progress, done); };
    if (!hierarchy.Close(keepGoing) || !SampleAll(image, hierarchy, params.NumberOfThreads, mesh, keepGoing))
    {
      return Status::Aborted();
    }
    fidelity = MeasureFidelity(
      image, components, params.MinimumComponentVoxels, mesh, params.NumberOfThreads, componentInMesh);
    if (params.Fidelity == 0.0)
    {
      passesEnd.End = PassesEnd::NoRefinementAsked;
      break;
    }

    if (!SplitOnePass(image, components, params, coverage.get(), result.BoundaryDistance,
          PassLimits{ minimumEdge, memoryLimit }, fidelity, componentInMesh, mesh, hierarchy, coverageProgress,
          passesEnd))
    {
      break;
    }
    ++result.Passes;
  }

  ResolveOwners(mesh, params.NumberOfThreads);
  // Spikes on the surface would keep their tips off the image boundary through deformation.
  const auto across = FaceNeighbours(mesh.Tets, hierarchy.Points().size(), params.NumberOfThreads);
  if (RemoveSurfaceEars(mesh.Tets, across, hierarchy.Points().size(), mesh.Labels,
        [&](std::int32_t label) { return label != NoLabel && image.IsTissue(label); }, NoLabel) > 0)
  {
    fidelity = MeasureFidelity(
      image, components, params.MinimumComponentVoxels, mesh, params.NumberOfThreads, componentInMesh);
  }

  fidelity = KeepComponentsAndMakeSound(image, components, params, hierarchy.Points(), across, mesh, componentInMesh,
    result.Relabelled);

  KeepTissueTets(image, hierarchy, mesh, out, result);
  for (const auto& entry : fidelity)
  {
    result.Tissues.push_back(entry.second);
  }
  result.LargestBoundaryGap = coverageProgress.LargestGap;
  const bool belowTarget = std::any_of(result.Tissues.begin(), result.Tissues.end(),
    [&](const TissueFidelity& t) { return t.F1 < params.Fidelity || t.F2 < params.Fidelity; });
  result.StopReason = StopReason(passesEnd, coverage != nullptr, coverageProgress, belowTarget);
  if (out.Tets.empty())
  {
    return Status::Error("no tet holds a majority of tissue voxels; use a smaller lattice size");
  }
  if (progress)
  {
    progress(1.0);
  }
  return Status::Ok();
}
} // namespace cbc3d
