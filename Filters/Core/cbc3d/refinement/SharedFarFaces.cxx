#include "cbc3d/refinement/SharedFarFaces.h"

#include "cbc3d/base/PointGrid.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace cbc3d
{
namespace
{
// Points at most this far apart (mm) are one: the ranks compute a lattice point alike to
// rounding, and lattice points lie 1/256 of a cube edge apart at the least.
constexpr double SamePoint = 1e-4;

// The face's three points, then its tet's fourth.
std::array<PointId, 4> Corners(const std::vector<Tet>& tets, const BoundaryCoverage::Face& face)
{
  std::array<PointId, 4> corners = { face.Points[0], face.Points[1], face.Points[2], 0 };
  for (const PointId p : tets[face.Tet])
    if (std::find(face.Points.begin(), face.Points.end(), p) == face.Points.end())
      corners[3] = p;
  return corners;
}

// Each received position's number among the distinct ones (the lowest index of its point).
std::vector<int> DistinctPoints(const std::vector<Eigen::Vector3d>& positions, const PointGrid& grid)
{
  std::vector<int> first(positions.size());
  for (std::size_t r = 0; r < positions.size(); ++r)
  {
    const int earlier = grid.Nearest(positions[r], SamePoint, [r](int i) { return std::size_t(i) < r; });
    first[r] = earlier < 0 ? int(r) : first[earlier];
  }
  return first;
}

// The faces (three points, then their tet's fourth: 12 numbers each) that this mesh holds.
std::vector<BoundaryCoverage::Face> MatchFaces(
  const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets, const std::vector<double>& all)
{
  std::vector<Eigen::Vector3d> positions(all.size() / 3);
  Eigen::AlignedBox3d box;
  for (std::size_t r = 0; r < positions.size(); ++r)
  {
    positions[r] = Eigen::Vector3d(all[3 * r], all[3 * r + 1], all[3 * r + 2]);
    box.extend(positions[r]);
  }
  if (positions.empty())
    return {};
  // About 64 cells along the longest side: a few points a cell.
  const PointGrid grid(positions, std::max(box.sizes().maxCoeff() / 64.0, 1e-3));
  const std::vector<int> distinct = DistinctPoints(positions, grid);
  std::vector<PointId> local(positions.size(), -1);
  for (std::size_t p = 0; p < points.size(); ++p)
  {
    const int r = grid.Nearest(points[p], SamePoint);
    if (r >= 0)
      local[distinct[r]] = PointId(p);
  }
  // The received faces whose four points this mesh has, by their sorted points.
  std::map<std::array<PointId, 4>, std::vector<std::array<PointId, 3>>> wanted;
  for (std::size_t f = 0; 4 * f < positions.size(); ++f)
  {
    std::array<PointId, 4> corners;
    for (int c = 0; c < 4; ++c)
      corners[c] = local[distinct[4 * f + c]];
    if (std::count(corners.begin(), corners.end(), -1) > 0)
      continue;
    std::array<PointId, 3> face = { corners[0], corners[1], corners[2] };
    std::sort(face.begin(), face.end());
    std::sort(corners.begin(), corners.end());
    wanted[corners].push_back(face);
  }
  std::set<std::pair<std::int64_t, std::array<PointId, 3>>> found;
  for (std::size_t t = 0; t < tets.size() && !wanted.empty(); ++t)
  {
    std::array<PointId, 4> corners = tets[t];
    std::sort(corners.begin(), corners.end());
    const auto match = wanted.find(corners);
    if (match != wanted.end())
      for (const auto& face : match->second)
        found.insert({ std::int64_t(t), face });
  }
  std::vector<BoundaryCoverage::Face> faces;
  for (const auto& [tet, face] : found)
    faces.push_back({ face, tet });
  return faces;
}

} // namespace

std::vector<BoundaryCoverage::Face> FindFarFacesOnRanks(const RankPasses& ranks, const BoundaryCoverage* coverage,
  const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets, const std::vector<std::int32_t>& labels,
  const std::vector<std::pair<std::int32_t, Eigen::Vector3d>>& far, const std::vector<char>& owned)
{
  std::vector<double> send;
  for (const auto& [label, centre] : far)
    send.insert(send.end(), { double(label), centre[0], centre[1], centre[2] });
  const std::vector<double> all = ranks.AllValues(send);
  std::vector<std::pair<std::int32_t, Eigen::Vector3d>> voxels(all.size() / 4);
  for (std::size_t v = 0; v < voxels.size(); ++v)
    voxels[v] = { std::int32_t(all[4 * v]), Eigen::Vector3d(all[4 * v + 1], all[4 * v + 2], all[4 * v + 3]) };
  // Each rank's offer per voxel: the distance, then the face.
  std::vector<double> offers;
  offers.reserve(13 * voxels.size());
  const auto nearest = coverage
    ? coverage->NearestOwnedFaces(points, tets, labels, voxels, owned)
    : std::vector<std::pair<double, BoundaryCoverage::Face>>(
        voxels.size(), { std::numeric_limits<double>::infinity(), BoundaryCoverage::Face{} });
  for (const auto& [distance, face] : nearest)
  {
    offers.push_back(distance);
    const bool any = std::isfinite(distance);
    for (const PointId p : any ? Corners(tets, face) : std::array<PointId, 4>{})
      for (int c = 0; c < 3; ++c)
        offers.push_back(any ? points[p][c] : 0.0);
  }
  const std::vector<double> everyOffer = ranks.AllValues(offers);
  const std::size_t rankCount = voxels.empty() ? 0 : everyOffer.size() / (13 * voxels.size());
  std::vector<double> winners;
  for (std::size_t v = 0; v < voxels.size(); ++v)
  {
    const double* best = nullptr;
    for (std::size_t r = 0; r < rankCount; ++r) // the first rank's of equals
    {
      const double* offer = everyOffer.data() + 13 * (r * voxels.size() + v);
      if (std::isfinite(offer[0]) && (!best || offer[0] < best[0]))
        best = offer;
    }
    if (best)
      winners.insert(winners.end(), best + 1, best + 13);
  }
  return MatchFaces(points, tets, winners);
}
} // namespace cbc3d
