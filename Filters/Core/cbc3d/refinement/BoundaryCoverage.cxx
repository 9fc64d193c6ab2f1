#include "cbc3d/refinement/BoundaryCoverage.h"

#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/Parallel.h"
#include "cbc3d/sampling/SurfacePoints.h"

#include <algorithm>
#include <limits>

namespace cbc3d
{
BoundaryCoverage::BoundaryCoverage(const LabelImage& image, const TissueComponents& components,
  int minimumVoxels, double reach, int numberOfThreads)
  : Reach(reach)
  , Threads(numberOfThreads)
{
  for (const auto& [label, voxels] : TissueBoundaryVoxels(image, numberOfThreads))
  {
    Tissue& tissue = this->Tissues[label];
    // Both ascend: the component runs are walked alongside the boundary voxels.
    auto run = components.Runs.begin();
    for (const std::int64_t v : voxels)
    {
      while (run->Last < v)
        ++run;
      if (components.Size[run->Component] >= minimumVoxels)
      {
        tissue.Centres.push_back(image.VoxelCentre(v));
      }
    }
    // Boundary voxels are dense: a grid of a few voxels per cell keeps each query short.
    tissue.Grid = std::make_unique<PointGrid>(tissue.Centres, 2.0 * image.Spacing.maxCoeff(), numberOfThreads);
  }
}

std::map<std::int32_t, std::vector<BoundaryCoverage::Face>> BoundaryCoverage::HeldSurfaces(
  std::size_t pointCount, const std::vector<Tet>& tets, const std::vector<std::int32_t>& labels) const
{
  // Only the held tissues' tets are searched (a face they share with any other tet is one of
  // theirs alone there), by their ids (not a copy of their corners), so the faces come in the
  // same order as over the whole mesh.
  const auto forEachHeldTet = [&](const auto& take) {
    std::int32_t lastLabel = 0;
    bool lastTracked = false;
    for (std::size_t t = 0; t < tets.size(); ++t)
    {
      if (t == 0 || labels[t] != lastLabel) // neighbouring tets mostly share a label
      {
        lastLabel = labels[t];
        lastTracked = this->Tissues.count(lastLabel) > 0;
      }
      if (lastTracked)
        take(t);
    }
  };
  std::size_t count = 0; // counted first: the list is the run's largest while it lives
  forEachHeldTet([&](std::size_t) { ++count; });
  std::vector<std::int32_t> subset;
  subset.reserve(count);
  forEachHeldTet([&](std::size_t t) { subset.push_back(static_cast<std::int32_t>(t)); });
  const auto bounding = [&](const MeshFace& face) {
    return face.TetCount != 2 || labels[face.Tets[0]] != labels[face.Tets[1]];
  };
  std::map<std::int32_t, std::vector<Face>> surfaces;
  for (const MeshFace& face : SelectMeshFaces(tets, subset, pointCount, this->Threads, bounding))
  {
    for (int side = 0; side < std::min(face.TetCount, 2); ++side)
    {
      surfaces[labels[face.Tets[side]]].push_back({ face.Points, face.Tets[side] });
    }
  }
  return surfaces;
}

BoundaryCoverage::Predicted BoundaryCoverage::Predict(
  const Tissue& tissue, const std::vector<Face>& faces, const std::vector<Eigen::Vector3d>& points) const
{
  // The surface's vertices, numbered 0..n-1 in ascending point order, and where deformation
  // would take each.
  std::vector<int> index(points.size(), -1);
  for (const Face& face : faces)
  {
    for (const PointId p : face.Points)
    {
      index[p] = 0;
    }
  }
  std::vector<PointId> vertices;
  for (std::size_t p = 0; p < points.size(); ++p)
  {
    if (index[p] == 0)
    {
      index[p] = static_cast<int>(vertices.size());
      vertices.push_back(static_cast<PointId>(p));
    }
  }
  const std::int64_t vertexCount = static_cast<std::int64_t>(vertices.size());
  Predicted predicted;
  predicted.Vertices.resize(vertexCount);
  std::vector<char> stranded(vertexCount, 0);
#pragma omp parallel for schedule(dynamic, 256) num_threads(ThreadCount(this->Threads))
  for (std::int64_t i = 0; i < vertexCount; ++i)
  {
    const Eigen::Vector3d& x = points[vertices[i]];
    const int nearest = tissue.Grid->Nearest(x, this->Reach);
    predicted.Vertices[i] = nearest < 0 ? x : tissue.Centres[nearest];
    stranded[i] = nearest < 0;
  }
  predicted.Centroids.reserve(faces.size());
  predicted.Stranded.reserve(faces.size());
  for (const Face& face : faces)
  {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    char any = 0;
    for (const PointId p : face.Points)
    {
      centroid += predicted.Vertices[index[p]] / 3.0;
      any = char(any | stranded[index[p]]);
    }
    predicted.Centroids.push_back(centroid);
    predicted.Stranded.push_back(any);
  }
  return predicted;
}

void BoundaryCoverage::FindTissueGaps(std::int32_t label, const Tissue& tissue, const std::vector<Face>& faces,
  const std::vector<Eigen::Vector3d>& points, double distance, Gaps& gaps) const
{
  const Predicted predicted = this->Predict(tissue, faces, points);
  for (std::size_t f = 0; f < faces.size(); ++f)
  {
    if (predicted.Stranded[f])
    {
      gaps.StrandedTets.push_back(faces[f].Tet);
    }
  }
  const double cell = std::max(distance, 1e-6);
  const PointGrid vertexGrid(predicted.Vertices, cell, this->Threads),
    faceGrid(predicted.Centroids, cell, this->Threads);
  const std::int64_t voxelCount = static_cast<std::int64_t>(tissue.Centres.size());
  std::vector<int> nearestFace(voxelCount, -1);
  std::vector<char> far(voxelCount, 0);
  const std::vector<int> nearestVertex = vertexGrid.NearestAnyOfAll(tissue.Centres, this->Threads);
  double largest = 0.0; // max and sum reductions are exact: the same for any thread count
  std::int64_t farCount = 0;
#pragma omp parallel for schedule(dynamic, 1024) reduction(max : largest) reduction(+ : farCount) num_threads(ThreadCount(this->Threads))
  for (std::int64_t i = 0; i < voxelCount; ++i)
  {
    const Eigen::Vector3d& centre = tissue.Centres[i];
    const double gap = (predicted.Vertices[nearestVertex[i]] - centre).norm();
    const bool counted = !this->Counted || this->Counted(centre);
    largest = counted ? std::max(largest, gap) : largest;
    if (gap > distance && counted)
    {
      // Over ranks, the ranks find the face together (NearestOwnedFaces).
      nearestFace[i] = this->Counted ? -1 : faceGrid.NearestAny(centre);
      far[i] = 1;
      ++farCount;
    }
  }
  gaps.LargestGap = std::max(gaps.LargestGap, largest);
  gaps.FarVoxels += farCount;
  for (std::int64_t i = 0; this->Counted && i < voxelCount; ++i)
  {
    if (far[i])
      gaps.Far.emplace_back(label, tissue.Centres[i]);
  }
  std::vector<char> taken(faces.size(), 0);
  for (const int f : nearestFace) // in voxel order: the same for any thread count
  {
    if (f >= 0 && !taken[f])
    {
      taken[f] = 1;
      gaps.FarFaces.push_back(faces[f]);
    }
  }
}

std::vector<std::pair<double, BoundaryCoverage::Face>> BoundaryCoverage::NearestOwnedFaces(
  const std::vector<Eigen::Vector3d>& points, const std::vector<Tet>& tets, const std::vector<std::int32_t>& labels,
  const std::vector<std::pair<std::int32_t, Eigen::Vector3d>>& voxels, const std::vector<char>& owned) const
{
  std::vector<std::pair<double, Face>> nearest(voxels.size(), { std::numeric_limits<double>::infinity(), Face{} });
  std::map<std::int32_t, std::vector<Face>> surfaces = this->HeldSurfaces(points.size(), tets, labels);
  for (const auto& [label, tissue] : this->Tissues)
  {
    const std::vector<Face>& faces = surfaces[label];
    if (faces.empty() || tissue.Centres.empty())
      continue;
    const Predicted predicted = this->Predict(tissue, faces, points);
    std::vector<Eigen::Vector3d> centroids;
    std::vector<std::size_t> faceOf;
    for (std::size_t f = 0; f < faces.size(); ++f)
    {
      if (owned[faces[f].Tet])
      {
        centroids.push_back(predicted.Centroids[f]);
        faceOf.push_back(f);
      }
    }
    if (centroids.empty())
      continue;
    const PointGrid grid(centroids, 2.0 * this->Reach, this->Threads);
    for (std::size_t v = 0; v < voxels.size(); ++v)
    {
      if (voxels[v].first != label)
        continue;
      const int found = grid.NearestAny(voxels[v].second);
      nearest[v] = { (centroids[found] - voxels[v].second).norm(), faces[faceOf[found]] };
    }
  }
  return nearest;
}

BoundaryCoverage::Gaps BoundaryCoverage::Find(const std::vector<Eigen::Vector3d>& points,
  const std::vector<Tet>& tets, const std::vector<std::int32_t>& labels, double distance) const
{
  std::map<std::int32_t, std::vector<Face>> surfaces = this->HeldSurfaces(points.size(), tets, labels);
  Gaps gaps;
  for (const auto& [label, tissue] : this->Tissues)
  {
    const std::vector<Face>& faces = surfaces[label];
    if (faces.empty() || tissue.Centres.empty())
    {
      const bool counted = !this->Counted ||
        std::any_of(tissue.Centres.begin(), tissue.Centres.end(), this->Counted);
      gaps.LargestGap = faces.empty() && !tissue.Centres.empty() && counted
        ? std::numeric_limits<double>::infinity()
        : gaps.LargestGap;
      continue;
    }
    this->FindTissueGaps(label, tissue, faces, points, distance, gaps);
  }
  std::sort(gaps.StrandedTets.begin(), gaps.StrandedTets.end());
  gaps.StrandedTets.erase(std::unique(gaps.StrandedTets.begin(), gaps.StrandedTets.end()), gaps.StrandedTets.end());
  return gaps;
}
} // namespace cbc3d
