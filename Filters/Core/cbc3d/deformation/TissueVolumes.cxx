#include "cbc3d/deformation/TissueVolumes.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/TaggedMesh.h"

#include <Eigen/Geometry>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cbc3d
{
namespace
{
constexpr std::int32_t Outside = std::numeric_limits<std::int32_t>::min();

// Half the cross product: the face's area times its unit normal.
Eigen::Vector3d AreaVector(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
  return 0.5 * (b - a).cross(c - a);
}
} // namespace

TissueVolumeKeeper::TissueVolumeKeeper(
  const TetMesh& mesh, std::map<std::int32_t, double> targets, double largestOffset)
  : TissueVolumeKeeper(mesh, FindMeshFaces(mesh), std::move(targets), largestOffset)
{
}

TissueVolumeKeeper::TissueVolumeKeeper(const TetMesh& mesh, const std::vector<MeshFace>& faces,
  std::map<std::int32_t, double> targets, double largestOffset)
  : Targets(std::move(targets))
  , LargestOffset(largestOffset)
{
  // The boundary and interface triangles, oriented out of their first side: the exporters'.
  TaggedMesh tagged;
  if (!BuildTaggedMesh(mesh, faces, Outside, tagged).IsOk())
  {
    return; // not conforming: ValidateTetMesh's business, not a volume's
  }
  for (std::size_t s = 0; s < tagged.Surfaces.size(); ++s)
  {
    this->Pairs.emplace_back(tagged.Surfaces[s].Sides[0], tagged.Surfaces[s].Sides[1]);
    for (std::size_t t = tagged.SurfaceStart[s]; t < tagged.SurfaceStart[s + 1]; ++t)
    {
      this->Faces.push_back({ tagged.Triangles[t].Points, int(s) });
    }
  }
}

std::map<std::int32_t, double> TissueVolumeKeeper::Volumes(const std::vector<Eigen::Vector3d>& x) const
{
  // Relative to one point of the mesh, so that far-off coordinates cost no precision.
  const Eigen::Vector3d origin = this->Faces.empty() ? Eigen::Vector3d::Zero() : x[this->Faces[0].Points[0]];
  std::map<std::int32_t, double> volumes;
  for (const InterfaceFace& face : this->Faces)
  {
    const Eigen::Vector3d a = x[face.Points[0]] - origin;
    const double cone = a.dot((x[face.Points[1]] - origin).cross(x[face.Points[2]] - origin)) / 6.0;
    const auto& [first, second] = this->Pairs[face.Pair];
    volumes[first] += cone;
    if (second != Outside)
    {
      volumes[second] -= cone;
    }
  }
  return volumes;
}

double TissueVolumeKeeper::LargestRelativeShortfall(const std::vector<Eigen::Vector3d>& x) const
{
  return this->LargestRelativeShortfall(this->Volumes(x));
}

double TissueVolumeKeeper::LargestRelativeShortfall(const std::map<std::int32_t, double>& volumes) const
{
  double largest = 0.0;
  for (const auto& [label, target] : this->Targets)
  {
    const auto found = volumes.find(label);
    if (found != volumes.end() && target > 0.0)
    {
      largest = std::max(largest, std::abs(target - found->second) / target);
    }
  }
  return largest;
}

TissueVolumeKeeper::AreaSums::AreaSums(const TissueVolumeKeeper& keeper, const std::vector<char>& moving)
  : Keeper(keeper)
{
  // Each face's area at each of its moving points, in face order, sorted by (point, pair): the
  // sort compares only those, so a face's place among its sum's faces is the same whatever
  // else the entries carry.
  struct Entry
  {
    PointId Point;
    int Pair;
    std::int32_t Face;
  };
  std::vector<Entry> entries;
  entries.reserve(3 * keeper.Faces.size());
  for (std::size_t f = 0; f < keeper.Faces.size(); ++f)
    for (const PointId p : keeper.Faces[f].Points)
      if (moving[p])
        entries.push_back({ p, keeper.Faces[f].Pair, static_cast<std::int32_t>(f) });
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.Point != b.Point ? a.Point < b.Point : a.Pair < b.Pair;
  });
  for (std::size_t i = 0; i < entries.size(); ++i)
  {
    if (i == 0 || entries[i].Point != entries[i - 1].Point || entries[i].Pair != entries[i - 1].Pair)
    {
      this->Sums.push_back({ entries[i].Point, entries[i].Pair, Eigen::Vector3d::Zero() });
      this->Start.push_back(static_cast<std::int64_t>(i));
    }
    this->FaceOf.push_back(entries[i].Face);
  }
  this->Start.push_back(static_cast<std::int64_t>(entries.size()));
}

std::vector<TissueVolumeKeeper::PointPairArea> TissueVolumeKeeper::AreaSums::At(
  const std::vector<Eigen::Vector3d>& x, int threads) const
{
  const auto& faces = this->Keeper.Faces;
  const std::int64_t faceCount = static_cast<std::int64_t>(faces.size());
  std::vector<Eigen::Vector3d> area(faces.size());
#pragma omp parallel for schedule(static) num_threads(ThreadCount(threads))
  for (std::int64_t f = 0; f < faceCount; ++f)
    area[f] = AreaVector(x[faces[f].Points[0]], x[faces[f].Points[1]], x[faces[f].Points[2]]);
  std::vector<PointPairArea> sums = this->Sums;
  const std::int64_t count = static_cast<std::int64_t>(sums.size());
#pragma omp parallel for schedule(static) num_threads(ThreadCount(threads))
  for (std::int64_t i = 0; i < count; ++i)
  {
    Eigen::Vector3d sum = area[this->FaceOf[this->Start[i]]];
    for (std::int64_t k = this->Start[i] + 1; k < this->Start[i + 1]; ++k)
      sum += area[this->FaceOf[k]];
    sums[i].Area = sum;
  }
  return sums;
}

// The offsets d (one per pair) that meet every target to first order with the least
// area-weighted squares: minimise d'Wd subject to M d = shortfall, so d = W^-1 M' (M W^-1 M')^+ s.
// M[t][p] is the volume tissue t gains when pair p's points move a unit along their normals:
// the sum over those points of the tissue's volume gradient (a third of its area vectors
// there: the derivative of a closed surface's volume) dotted with the pair's unit normal there.
Eigen::VectorXd TissueVolumeKeeper::InterfaceOffsets(const std::vector<PointPairArea>& areas,
  const std::map<std::int32_t, double>& volumes, const std::map<std::int32_t, double>& aims) const
{
  std::map<std::int32_t, int> row;
  for (const auto& [label, target] : this->Targets)
  {
    if (volumes.count(label))
    {
      row.emplace(label, int(row.size()));
    }
  }
  const int pairs = int(this->Pairs.size());
  if (row.empty())
  {
    return Eigen::VectorXd::Zero(pairs);
  }
  Eigen::MatrixXd gain = Eigen::MatrixXd::Zero(Eigen::Index(row.size()), pairs);
  Eigen::VectorXd weight = Eigen::VectorXd::Constant(pairs, 1e-12);
  for (std::size_t begin = 0, end = 0; begin < areas.size(); begin = end)
  {
    while (end < areas.size() && areas[end].Point == areas[begin].Point)
    {
      ++end;
    }
    for (std::size_t i = begin; i < end; ++i) // the tissue whose gradient this entry adds to
    {
      const auto& [first, second] = this->Pairs[areas[i].Pair];
      for (const auto& [label, sign] : { std::make_pair(first, 1.0), std::make_pair(second, -1.0) })
      {
        const auto r = row.find(label);
        if (r == row.end())
        {
          continue;
        }
        const Eigen::Vector3d gradient = sign * areas[i].Area / 3.0;
        for (std::size_t j = begin; j < end; ++j) // the pair that moves
        {
          const double length = areas[j].Area.norm();
          if (length > 0.0)
          {
            gain(r->second, areas[j].Pair) += gradient.dot(areas[j].Area / length);
          }
        }
      }
    }
    for (std::size_t j = begin; j < end; ++j)
    {
      weight[areas[j].Pair] += areas[j].Area.norm() / 3.0;
    }
  }
  Eigen::VectorXd shortfall(row.size());
  for (const auto& [label, r] : row)
  {
    const auto aim = aims.find(label);
    shortfall[r] = (aim != aims.end() ? aim->second : this->Targets.at(label)) - volumes.at(label);
  }
  const Eigen::MatrixXd spread = weight.cwiseInverse().asDiagonal() * gain.transpose();
  const Eigen::VectorXd multipliers = (gain * spread).completeOrthogonalDecomposition().solve(shortfall);
  Eigen::VectorXd offsets = spread * multipliers;
  for (Eigen::Index p = 0; p < offsets.size(); ++p)
  {
    offsets[p] = std::clamp(offsets[p], -this->LargestOffset, this->LargestOffset);
  }
  return offsets;
}

double TissueVolumeKeeper::OffsetGoals(std::vector<Eigen::Vector3d>& goals, const std::vector<char>& moving,
  const std::map<std::int32_t, double>& aims) const
{
  return this->OffsetGoals(goals, AreaSums(*this, moving), this->Volumes(goals), aims, 1);
}

double TissueVolumeKeeper::OffsetGoals(std::vector<Eigen::Vector3d>& goals, const AreaSums& sums,
  const std::map<std::int32_t, double>& volumes, const std::map<std::int32_t, double>& aims, int threads) const
{
  if (this->Faces.empty() || this->Targets.empty())
  {
    return 0.0;
  }
  const std::vector<PointPairArea> areas = sums.At(goals, threads);
  const Eigen::VectorXd offsets = this->InterfaceOffsets(areas, volumes, aims);
  for (const PointPairArea& entry : areas)
  {
    const double length = entry.Area.norm();
    if (length > 0.0)
    {
      goals[entry.Point] += offsets[entry.Pair] * entry.Area / length;
    }
  }
  return offsets.size() ? offsets.cwiseAbs().maxCoeff() : 0.0;
}
} // namespace cbc3d
