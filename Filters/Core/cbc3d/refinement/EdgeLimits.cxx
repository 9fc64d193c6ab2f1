#include "cbc3d/refinement/EdgeLimits.h"

#include "cbc3d/base/TetGeometry.h"

#include <algorithm>
#include <map>
#include <sstream>
#include <string>

namespace cbc3d
{
namespace
{
// The tightest positive edge limit among `label` and the labels whose voxels the tet holds; 0
// when none of them has a limit.
double TightestLimit(const LabelImage& image, const RefinementParams& params, std::int32_t label,
  const LabelCounts& counts)
{
  double limit = 0.0;
  const auto take = [&](std::int32_t tissue) {
    if (!IsTissueLabel(image, tissue))
      return;
    const double own = params.MaximumEdge.Of(tissue);
    if (own > 0.0 && (limit == 0.0 || own < limit))
      limit = own;
  };
  take(label);
  for (const auto& entry : counts.Counts)
    take(entry.first);
  return limit;
}

// Lengths are compared with a relative slack, so that an edge of exactly the limit passes.
bool Longer(double length, double limit)
{
  return length > limit * (1.0 + 1e-9);
}
} // namespace

std::size_t MarkForMaximumEdge(const LabelImage& image, const RefinementParams& params,
  const RedGreenMesh& hierarchy, const LabelledMesh& mesh, std::vector<char>& marked)
{
  std::size_t count = 0;
  if (!params.MaximumEdge.Any())
  {
    return count; // the default: no pass pays for a look at every tet
  }
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const std::int64_t red = mesh.Source[t];
    if (marked[red] == MarkedForEdgeLimit)
      continue;
    const double limit = TightestLimit(image, params, mesh.Labels[t], mesh.Counts[t]);
    if (limit > 0.0 && Longer(hierarchy.LongestEdge(static_cast<std::size_t>(red)), limit))
    {
      marked[red] = MarkedForEdgeLimit;
      ++count;
    }
  }
  return count;
}

bool SplitOverlongTets(const LabelImage& image, const RefinementParams& params, RedGreenMesh& hierarchy,
  const LabelledMesh& mesh)
{
  std::vector<char> split(hierarchy.Reds().size(), 0);
  bool any = false;
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const std::int32_t label = mesh.Labels[t];
    const auto red = static_cast<std::size_t>(mesh.Source[t]);
    if (split[red] || !IsTissueLabel(image, label) || params.MaximumEdge.Of(label) <= 0.0)
      continue;
    if (Longer(hierarchy.LongestEdge(red), params.MaximumEdge.Of(label)) &&
      hierarchy.ShortestEdge(red) / 2.0 >= params.MinimumEdgeLength * (1.0 - 1e-9))
    {
      split[red] = 1;
      any = true;
    }
  }
  for (std::size_t red = 0; red < split.size(); ++red)
  {
    if (split[red])
      hierarchy.SplitRed(red);
  }
  return any;
}

std::size_t CountOverlongEdges(const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets,
  const std::vector<std::int32_t>& labels, const LabelImage& image, const RefinementParams& params)
{
  std::size_t count = 0;
  if (!params.MaximumEdge.Any())
  {
    return count;
  }
  for (std::size_t t = 0; t < tets.size(); ++t)
  {
    const double limit = IsTissueLabel(image, labels[t]) ? params.MaximumEdge.Of(labels[t]) : 0.0;
    count += limit > 0.0 && Longer(LongestEdgeOf(points, tets[t]), limit);
  }
  return count;
}

Status CheckEdgeLimitsAboveFloor(const RefinementParams& params)
{
  const double minimumEdge = params.MinimumEdgeLength;
  std::map<std::string, double> limits;
  if (params.MaximumEdge.All > 0.0)
    limits["the maximum edge length"] = params.MaximumEdge.All;
  for (const auto& [label, length] : params.MaximumEdge.ByTissue)
    limits["the maximum edge length of tissue " + std::to_string(label)] = length;
  for (const auto& [what, length] : limits)
  {
    if (length < minimumEdge * (1.0 - 1e-9))
    {
      std::ostringstream message;
      message << what << " (" << length << " mm) is below the minimum edge length (" << minimumEdge << " mm)";
      return Status::Error(message.str());
    }
  }
  return Status::Ok();
}
} // namespace cbc3d
