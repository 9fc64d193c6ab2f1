#include "cbc3d/refinement/CoveragePasses.h"

#include "cbc3d/refinement/SharedFarFaces.h"

#include <algorithm>
#include <cmath>

namespace cbc3d
{
namespace
{
// A face's longest edge e (points e and e + 1), the first of equals.
int LongestEdge(const std::vector<Eigen::Vector3d>& x, const BoundaryCoverage::Face& face)
{
  int longest = 0;
  auto length = [&](int e) { return (x[face.Points[e]] - x[face.Points[(e + 1) % 3]]).norm(); };
  for (int e = 1; e < 3; ++e)
  {
    longest = length(e) > length(longest) ? e : longest;
  }
  return longest;
}

// The same, with edges of equal length (to rounding) told apart by where they are, not by how
// a rank numbers its points: every rank holding the face splits the same edge.
int LongestEdgeByPosition(const std::vector<Eigen::Vector3d>& x, const BoundaryCoverage::Face& face)
{
  auto length = [&](int e) { return (x[face.Points[e]] - x[face.Points[(e + 1) % 3]]).norm(); };
  auto middle = [&](int e) { return 0.5 * (x[face.Points[e]] + x[face.Points[(e + 1) % 3]]); };
  auto before = [&](int e, int f) { // e's middle first along x, then y, then z
    const Eigen::Vector3d d = middle(e) - middle(f);
    for (int c = 0; c < 3; ++c)
      if (std::abs(d[c]) > 1e-6)
        return d[c] < 0.0;
    return false;
  };
  int longest = 0;
  for (int e = 1; e < 3; ++e)
  {
    const double a = length(e), b = length(longest);
    if (a > b * (1.0 + 1e-9) || (a >= b * (1.0 - 1e-9) && before(e, longest)))
      longest = e;
  }
  return longest;
}
} // namespace

bool CoverageGoesOn(BoundaryCoverage::Gaps& gaps, CoverageProgress& progress, const RankPasses* ranks)
{
  if (ranks)
  {
    // Progress is the whole image's: every rank stalls, or goes on, together.
    double far = double(gaps.FarVoxels);
    ranks->SumAndMax(far, gaps.LargestGap);
    gaps.FarVoxels = std::llround(far);
  }
  BoundaryCoverage::Gaps before;
  before.LargestGap = progress.LargestGap;
  before.FarVoxels = progress.FarVoxels;
  progress.LargestGap = gaps.LargestGap;
  progress.FarVoxels = gaps.FarVoxels;
  progress.Stalled = before.FarVoxels >= 0 && !gaps.NarrowerThan(before);
  return !progress.Stalled;
}

// Where the surface would stay far from the image boundary (more than `distance`): a new
// surface vertex on the longest edge of the face nearest to a far boundary voxel (a green split
// of the tets around the edge, into `bisect`), or a red split of the leaf where that edge is not
// one of the leaf's own; and a red split of the tets with a vertex that cannot reach the
// boundary. Returns whether any split was wanted (at the depth limit or not); none once a pass
// brings neither the farthest voxel nearer nor fewer voxels far (`progress` then stalls).
bool MarkForCoverage(const LabelImage& image, const BoundaryCoverage& coverage, double distance, const RedGreenMesh& hierarchy,
  const LabelledMesh& mesh, double minimumEdge, CoverageProgress& progress, std::vector<char>& marked,
  std::vector<std::pair<PointId, PointId>>& bisect, const RankPasses* ranks)
{
  const auto& x = hierarchy.Points();
  BoundaryCoverage::Gaps gaps = coverage.Find(x, mesh.Tets, mesh.Labels, distance);
  if (!CoverageGoesOn(gaps, progress, ranks))
  {
    return false;
  }
  if (ranks)
  {
    gaps.FarFaces = FindFarFacesOnRanks(
      *ranks, &coverage, x, mesh.Tets, mesh.Labels, gaps.Far, RankOwnedTets(image, x, mesh.Tets, *ranks));
  }
  const bool wanted = !gaps.FarFaces.empty() || !gaps.StrandedTets.empty();
  for (const std::int64_t t : gaps.StrandedTets)
  {
    marked[mesh.Source[t]] = 1;
  }
  for (const BoundaryCoverage::Face& face : gaps.FarFaces)
  {
    const int longest = ranks ? LongestEdgeByPosition(x, face) : LongestEdge(x, face);
    auto length = [&](int e) { return (x[face.Points[e]] - x[face.Points[(e + 1) % 3]]).norm(); };
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
  result.BoundaryDistance =
    params.BoundaryDistance > 0.0 ? params.BoundaryDistance : DefaultBoundaryDistance(longest);
  // Deformation moves a vertex by about an element size: the lattice's shortest edge.
  auto coverage = std::make_unique<BoundaryCoverage>(image, components, params.MinimumComponentVoxels,
    hierarchy.ShortestEdge(0), params.NumberOfThreads);
  if (const RankPasses* ranks = params.Ranks.get())
  {
    const Eigen::Vector3d axis = image.Direction.col(ranks->Axis);
    coverage->SetCounted([&image, ranks, axis](const Eigen::Vector3d& centre) {
      return ranks->Owns(axis.dot(centre - image.Origin));
    });
  }
  return coverage;
}
} // namespace cbc3d
