#include "cbc3d/soundlabels/StrayComponents.h"

#include "cbc3d/base/DisjointSets.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>

namespace cbc3d
{
namespace
{
// The pieces of every class; node tets.size() is the outside, joined to the boundary's
// background tets.
DisjointSets FindPieces(const std::vector<Tet>& tets, const std::vector<TetNeighbours>& across,
  std::int32_t background, const std::vector<std::int32_t>& classes)
{
  const std::int64_t outside = static_cast<std::int64_t>(tets.size());
  DisjointSets pieces(tets.size() + 1);
  for (std::int64_t t = 0; t < outside; ++t)
    for (const std::int64_t n : across[t])
    {
      if (n >= 0 && classes[n] == classes[t])
        pieces.Join(t, n);
      else if (n < 0 && classes[t] == background)
        pieces.Join(t, outside);
    }
  return pieces;
}

// The pieces lying against a tissue of another class.
std::vector<char> EmbeddedPieces(DisjointSets& pieces, const std::vector<TetNeighbours>& across,
  std::int32_t background, const std::vector<std::int32_t>& classes)
{
  std::vector<char> embedded(classes.size() + 1, 0);
  for (std::size_t t = 0; t < classes.size(); ++t)
    for (const std::int64_t n : across[t])
      if (n >= 0 && classes[n] != classes[t] && classes[n] != background)
        embedded[pieces.Find(static_cast<std::int64_t>(t))] = 1;
  return embedded;
}

// Marks the piece holding most voxels of each image region (ties: the smaller root); a speck's
// piece only where it is embedded.
std::vector<char> KeptPieces(DisjointSets& pieces, const VoxelOwners& voxelOwner,
  const ImageRegions& regions, const std::vector<std::int32_t>& classes, const std::vector<char>& embedded)
{
  const std::int64_t outside = static_cast<std::int64_t>(classes.size());
  std::vector<std::unordered_map<std::int64_t, std::int64_t>> held(regions.ClassOfRegion.size());
  // Consecutive voxels of one region and one owner are counted together: a tet spans many
  // voxels of a row, so the map is looked up per stretch, not per voxel (every tissue voxel is
  // visited, in every cleanup round).
  std::int32_t lastRegion = -1, lastOwner = -1;
  std::int64_t stretch = 0;
  auto flush = [&]() {
    if (stretch > 0 && lastRegion >= 0 && lastOwner >= 0 && classes[lastOwner] == regions.ClassOfRegion[lastRegion])
      held[lastRegion][pieces.Find(lastOwner)] += stretch;
    stretch = 0;
  };
  auto hold = [&](std::int32_t region, std::int32_t owner) {
    if (region != lastRegion || owner != lastOwner)
    {
      flush();
      lastRegion = region;
      lastOwner = owner;
    }
    ++stretch;
  };
  // Counts are whole numbers, and the choice below does not depend on the order of the pieces.
  regions.Tissues->ForEachVoxel([&](std::int64_t v, std::int32_t component) { hold(component, voxelOwner[v]); });
  // Only the kept cavities' runs: the outside's, most of the background, count for nothing.
  for (const RunComponents::Run& run : regions.Gaps.Runs)
    if (regions.RegionOfGap[run.Component] >= 0)
      for (std::int64_t v = run.First; v <= run.Last; ++v)
        hold(regions.RegionOfGap[run.Component], voxelOwner[v]);
  flush();
  std::vector<char> kept(classes.size() + 1, 0);
  kept[pieces.Find(outside)] = 1;
  for (std::size_t region = 0; region < held.size(); ++region)
  {
    std::int64_t best = -1, most = 0;
    for (const auto& [piece, count] : held[region])
      if (count > most || (count == most && piece < best))
      {
        best = piece;
        most = count;
      }
    if (best >= 0 && (!regions.Speck[region] || embedded[best]))
      kept[best] = 1;
  }
  return kept;
}
} // namespace

std::int64_t RemoveStrayComponents(const std::vector<Tet>& tets,
  const std::vector<TetNeighbours>& across, std::int32_t background,
  const ClassVotes& votes, const VoxelOwners& voxelOwner, const ImageRegions& regions,
  std::vector<std::int32_t>& classes, std::vector<std::int64_t>& changed)
{
  DisjointSets pieces = FindPieces(tets, across, background, classes);
  const std::vector<char> kept =
    KeptPieces(pieces, voxelOwner, regions, classes, EmbeddedPieces(pieces, across, background, classes));
  const std::int64_t count = static_cast<std::int64_t>(tets.size());
  std::vector<char> stray(count, 0);
  std::vector<char> strayRoot(count + 1, 0);
  for (std::int64_t t = 0; t < count; ++t)
  {
    const std::int64_t root = pieces.Find(t);
    stray[t] = !kept[root];
    strayRoot[root] |= stray[t];
  }
  // From the rim inwards: a stray tet next to a settled one takes its best neighbouring class.
  std::vector<std::int64_t> rim;
  for (std::int64_t t = 0; t < count; ++t)
    if (stray[t] && std::any_of(across[t].begin(), across[t].end(), [&](std::int64_t n) { return n >= 0 && !stray[n]; }))
      rim.push_back(t);
  std::vector<char> queued(stray.begin(), stray.end());
  for (const std::int64_t t : rim)
    queued[t] = 2;
  for (std::size_t next = 0; next < rim.size(); ++next)
  {
    const std::int64_t t = rim[next];
    std::int32_t to = classes[t];
    std::int64_t most = -1;
    for (const std::int64_t n : across[t])
      if (n >= 0 && !stray[n] && classes[n] != classes[t] && votes(t, classes[n]) > most)
      {
        most = votes(t, classes[n]);
        to = classes[n];
      }
    if (most < 0 && std::find(across[t].begin(), across[t].end(), -1) != across[t].end())
      to = background; // only the outside around it
    stray[t] = 0;
    if (to != classes[t])
    {
      classes[t] = to;
      changed.push_back(t);
    }
    for (const std::int64_t n : across[t])
      if (n >= 0 && queued[n] == 1)
      {
        queued[n] = 2;
        rim.push_back(n);
      }
  }
  return std::count(strayRoot.begin(), strayRoot.end(), 1);
}
} // namespace cbc3d
