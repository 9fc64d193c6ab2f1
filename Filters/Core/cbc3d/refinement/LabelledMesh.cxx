#include "cbc3d/refinement/LabelledMesh.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/TetGeometry.h"

#include <algorithm>

namespace cbc3d
{
namespace
{
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

// Per tissue label, the voxel centres in its tets and those of them of its label (whole
// numbers of sample weights, summed exactly: the same in any order, so in parallel).
void CountTissueVoxelsInTets(const LabelImage& image, const LabelledMesh& mesh, int threads,
  std::map<std::int32_t, double>& inTets, std::map<std::int32_t, double>& shared,
  const std::vector<char>* counted = nullptr)
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
      if (mesh.HoldsVoxelCentres[t] && IsTissueLabel(image, label) && (!counted || (*counted)[t]))
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
// The counts of MeasureFidelity over this rank's slab alone, summed over the ranks: voxels by
// their centres, tets by their centres (the slabs' borders lie where neither can, RankPasses).
void CountRankSlab(const LabelImage& image, const TissueComponents& components, const LabelledMesh& mesh,
  const std::vector<Eigen::Vector3d>& points, const RankPasses& ranks, int threads,
  std::map<std::int32_t, double>& inImage, std::map<std::int32_t, double>& inTets,
  std::map<std::int32_t, double>& shared)
{
  const int axis = ranks.Axis;
  const std::vector<char> owned = RankOwnedTets(image, points, mesh.Tets, ranks);
  CountTissueVoxelsInTets(image, mesh, threads, inTets, shared, &owned);
  for (const auto& run : components.Runs)
  {
    const std::array<int, 3> first = image.VoxelCoordinates(run.First);
    const std::int64_t length = run.Last - run.First + 1;
    // Runs go along x: only slabs across x cut one; another axis keeps or leaves it whole.
    std::int64_t voxels = axis != 0 && ranks.Owns(image.Spacing[axis] * first[axis]) ? length : 0;
    for (std::int64_t v = 0; axis == 0 && v < length; ++v)
    {
      voxels += ranks.Owns(image.Spacing[0] * (first[0] + v));
    }
    inImage[components.Label[run.Component]] += double(voxels) * double(VoxelWeight);
  }
  std::map<std::int32_t, std::array<double, 3>> sums;
  for (const auto& [label, voxels] : inImage)
    sums[label][0] = voxels;
  for (const auto& [label, voxels] : inTets)
    sums[label][1] = voxels;
  for (const auto& [label, voxels] : shared)
    sums[label][2] = voxels;
  ranks.SumByLabel(sums);
  inImage.clear();
  inTets.clear();
  shared.clear();
  for (const auto& [label, values] : sums)
  {
    inImage[label] = values[0];
    inTets[label] = values[1];
    shared[label] = values[2];
  }
}

// Over ranks: a component is in the mesh where any rank finds a voxel of it in a tet of its label.
void AnyRankHasComponent(const TissueComponents& components, const RankPasses& ranks, std::vector<char>& componentInMesh)
{
  std::map<std::int64_t, double> found;
  for (std::size_t c = 0; c < componentInMesh.size(); ++c)
    if (componentInMesh[c])
      found[components.WholeId[c]] = 1.0;
  ranks.SumByKey(found);
  for (std::size_t c = 0; c < componentInMesh.size(); ++c)
    componentInMesh[c] = found.count(components.WholeId[c]) > 0;
}
} // namespace

std::vector<char> RankOwnedTets(const LabelImage& image, const std::vector<Eigen::Vector3d>& points,
  const std::vector<Tet>& tets, const RankPasses& ranks)
{
  const Eigen::Vector3d toAxis = image.Direction.col(ranks.Axis);
  std::vector<char> owned(tets.size(), 0);
  for (std::size_t t = 0; t < tets.size(); ++t)
  {
    const Tet& tet = tets[t];
    const Eigen::Vector3d centre = Centroid(points[tet[0]], points[tet[1]], points[tet[2]], points[tet[3]]);
    owned[t] = ranks.Owns(toAxis.dot(centre - image.Origin));
  }
  return owned;
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

// F1 and F2 of every tissue, and its components kept in the mesh.
std::map<std::int32_t, TissueFidelity> MeasureFidelity(const LabelImage& image,
  const TissueComponents& components, int minimumVoxels, const LabelledMesh& mesh, int threads,
  std::vector<char>& componentInMesh, const RankPasses* ranks, const std::vector<Eigen::Vector3d>* points)
{
  std::map<std::int32_t, double> inTets, shared, inImage;
  if (ranks && points)
  {
    CountRankSlab(image, components, mesh, *points, *ranks, threads, inImage, inTets, shared);
  }
  else
  {
    for (std::size_t c = 0; c < components.Label.size(); ++c)
    {
      inImage[components.Label[c]] += double(components.Size[c]) * double(VoxelWeight);
    }
    CountTissueVoxelsInTets(image, mesh, threads, inTets, shared);
  }
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
      if (ranks && !ranks->OwnsVoxel(image, v))
      {
        continue; // another rank's voxel: its tet there may be its alone
      }
      const std::int32_t owner = mesh.OwnerOf(v);
      if (owner >= 0 && mesh.Labels[owner] == components.Label[component])
      {
#pragma omp atomic write
        componentInMesh[component] = 1;
        found = 1;
      }
    }
  }
  if (ranks)
  {
    AnyRankHasComponent(components, *ranks, componentInMesh);
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
} // namespace cbc3d
