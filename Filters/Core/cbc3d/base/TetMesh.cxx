#include "cbc3d/base/TetMesh.h"

#include "cbc3d/base/TetGeometry.h"

#include <limits>
#include <sstream>
#include <stdexcept>

namespace cbc3d
{
void CheckPointCount(std::size_t points)
{
  if (points > MaxPoints)
  {
    throw std::length_error("a mesh of more than 2^31 - 1 points: use a larger --bcc-size or a --max-tets "
                            "budget, or mesh it in pieces (over MPI ranks)");
  }
}

void CheckTetCount(std::size_t tets)
{
  if (tets > std::size_t(std::numeric_limits<std::int32_t>::max()))
  {
    throw std::length_error("a mesh of more than 2^31 - 1 tets: mesh it in pieces (over MPI ranks)");
  }
}

Status ValidateTetMesh(const TetMesh& mesh)
{
  if (mesh.Labels.size() != mesh.Tets.size())
  {
    return Status::Error("the mesh has a different number of labels and tets");
  }
  if (mesh.Points.size() > MaxPoints)
  {
    return Status::Error("the mesh has more than 2^31 - 1 points");
  }
  const PointId pointCount = static_cast<PointId>(mesh.Points.size());
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const Tet& tet = mesh.Tets[t];
    for (const PointId id : tet)
    {
      if (id < 0 || id >= pointCount)
      {
        std::ostringstream msg;
        msg << "tet " << t << " refers to point " << id << " of " << pointCount;
        return Status::Error(msg.str());
      }
    }
    const auto& p = mesh.Points;
    if (!(SignedVolume(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]) > 0.0))
    {
      std::ostringstream msg;
      msg << "tet " << t << " is inverted or flat";
      return Status::Error(msg.str());
    }
  }
  return Status::Ok();
}

double LongestEdgeOf(const std::vector<Eigen::Vector3d>& points, const Tet& tet)
{
  return LongestEdge(points[tet[0]], points[tet[1]], points[tet[2]], points[tet[3]]);
}
} // namespace cbc3d
