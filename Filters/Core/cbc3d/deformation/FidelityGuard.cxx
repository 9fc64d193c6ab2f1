#include "cbc3d/deformation/FidelityGuard.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/sampling/SurfacePoints.h"

#include <algorithm>

namespace cbc3d
{
namespace
{
// The mean length of the edges of the tissues' surface triangles (0 without any).
double MeanSurfaceEdge(const TetMesh& mesh, const std::vector<MeshFace>& faces)
{
  double sum = 0.0;
  std::size_t count = 0;
  for (const MeshFace& face : faces)
  {
    if (face.TetCount == 1 || (face.TetCount == 2 && mesh.Labels[face.Tets[0]] != mesh.Labels[face.Tets[1]]))
    {
      const auto& p = face.Points;
      sum += (mesh.Points[p[0]] - mesh.Points[p[1]]).norm() + (mesh.Points[p[1]] - mesh.Points[p[2]]).norm() +
        (mesh.Points[p[2]] - mesh.Points[p[0]]).norm();
      count += 3;
    }
  }
  return count > 0 ? sum / double(count) : 0.0;
}
} // namespace

FidelityGuard::FidelityGuard(const LabelImage& image, const TissueVoxels& boundary, const TetMesh& mesh,
  const std::vector<MeshFace>& faces, double cell, int threads, const std::function<bool()>& keepGoing,
  const std::vector<char>& fixed)
  : Cell(cell)
  , VertexCell(std::max(cell, MeanSurfaceEdge(mesh, faces)))
  , Threads(threads)
{
  // The vertices are sparser than the boundary voxels where the voxels are small (4 times
  // finer voxels, the same tets: 64 times the cells of one voxel, nearly all empty, to build
  // at every snapshot and to cross at every search). A cell of about an edge holds a vertex
  // or a few. The answers are the same for any cell size (PointGrid.h).
  const auto vertices = TissueSurfaceVertices(mesh, faces);
  for (const auto& [label, ids] : vertices)
  {
    const auto found = boundary.find(label);
    if (found != boundary.end())
    {
      Tissue tissue{ label, ids };
      tissue.Counted.reserve(fixed.empty() ? 0 : ids.size());
      tissue.Voxels.reserve(found->second.size()); // (grown one by one, they took up to twice)
      for (std::size_t v = 0; !fixed.empty() && v < ids.size(); ++v)
      {
        tissue.Counted.push_back(fixed[ids[v]] ? 0 : 1);
      }
      for (const std::int64_t voxel : found->second)
      {
        tissue.Voxels.push_back(image.VoxelCentre(voxel));
      }
      this->Tissues.push_back(std::move(tissue));
    }
  }
  for (Tissue& tissue : this->Tissues)
  {
    if (!keepGoing())
    {
      return;
    }
    tissue.Grid = std::make_unique<PointGrid>(tissue.Voxels, cell, this->Threads);
    tissue.Current = std::make_unique<Snapshot>(tissue.Vertices, mesh.Points, this->VertexCell);
    tissue.Hausdorff = this->Measure(tissue, *tissue.Current);
  }
}

std::size_t FidelityGuard::Hold(const std::vector<Eigen::Vector3d>& trial, std::vector<double>& share,
  const std::function<bool()>& keepGoing) const
{
  std::vector<char> hold(trial.size(), 0);
  for (const Tissue& tissue : this->Tissues)
  {
    if (!keepGoing())
    {
      return 0;
    }
    const double limit = tissue.Hausdorff * (1.0 + 1e-12);
    const std::int64_t vertexCount = static_cast<std::int64_t>(tissue.Vertices.size());
#pragma omp parallel for schedule(dynamic, 256) num_threads(ThreadCount(this->Threads))
    for (std::int64_t i = 0; i < vertexCount; ++i)
    {
      const PointId v = tissue.Vertices[i];
      if (share[v] > 0.0 && tissue.Grid->Nearest(trial[v], limit) < 0)
      {
        hold[v] = 1; // each vertex appears once in a tissue's list
      }
    }
    const Snapshot after(tissue.Vertices, trial, this->VertexCell);
    const Snapshot& current = *tissue.Current;
    const std::int64_t voxelCount = static_cast<std::int64_t>(tissue.Voxels.size());
#pragma omp parallel for schedule(dynamic, 256) num_threads(ThreadCount(this->Threads))
    for (std::int64_t i = 0; i < voxelCount; ++i)
    {
      const Eigen::Vector3d& voxel = tissue.Voxels[i];
      // Still within the limit of its nearest vertex after that vertex's move: covered,
      // with no search (most voxels, as most moves are short).
      const int nearest = current.NearestVertex[i];
      const Eigen::Vector3d& was = current.Points[nearest];
      if ((voxel - was).norm() + (trial[tissue.Vertices[nearest]] - was).norm() <= limit)
      {
        continue;
      }
      if (after.Grid->Nearest(voxel, limit) < 0)
      {
        const int covering = tissue.Current->Grid->Nearest(voxel, limit);
        if (covering >= 0 && share[tissue.Vertices[covering]] > 0.0)
        {
#pragma omp atomic write
          hold[tissue.Vertices[covering]] = 1;
        }
      }
    }
  }
  std::size_t held = 0;
  for (std::size_t p = 0; p < hold.size(); ++p)
  {
    if (hold[p])
    {
      share[p] = 0.0;
      ++held;
    }
  }
  return held;
}

bool FidelityGuard::AcceptIfNoneGrows(const std::vector<Eigen::Vector3d>& points, const std::function<bool()>& keepGoing)
{
  std::vector<std::unique_ptr<Snapshot>> snapshots;
  std::vector<double> measured;
  for (const Tissue& tissue : this->Tissues)
  {
    if (!keepGoing())
    {
      return false;
    }
    snapshots.push_back(std::make_unique<Snapshot>(tissue.Vertices, points, this->VertexCell));
    measured.push_back(this->Measure(tissue, *snapshots.back()));
    if (measured.back() > tissue.Hausdorff * (1.0 + 1e-12))
    {
      return false;
    }
  }
  for (std::size_t t = 0; t < measured.size(); ++t)
  {
    this->Tissues[t].Hausdorff = measured[t];
    this->Tissues[t].Current = std::move(snapshots[t]);
  }
  return true;
}

void FidelityGuard::Accept(const std::vector<Eigen::Vector3d>& points, const std::function<bool()>& keepGoing)
{
  for (Tissue& tissue : this->Tissues)
  {
    if (!keepGoing())
    {
      return;
    }
    tissue.Current = std::make_unique<Snapshot>(tissue.Vertices, points, this->VertexCell);
    tissue.Hausdorff = std::min(tissue.Hausdorff, this->Measure(tissue, *tissue.Current));
  }
}

void FidelityGuard::Steer(const std::vector<double>& reach, const std::vector<double>& search,
  std::vector<Eigen::Vector3d>& goal, std::vector<char>& steered) const
{
  goal.assign(reach.size(), Eigen::Vector3d::Zero());
  steered.assign(reach.size(), 0);
  std::vector<double> farthest(reach);
  auto offer = [&](PointId v, const Eigen::Vector3d& voxel, double d) {
    if (d > farthest[v])
    {
      farthest[v] = d;
      goal[v] = voxel;
      steered[v] = 1;
    }
  };
  for (const Tissue& tissue : this->Tissues) // voxels far from every vertex first
  {
    const Snapshot& current = *tissue.Current;
    for (std::size_t i = 0; i < tissue.Voxels.size(); ++i)
    {
      const int nearest = current.NearestVertex[i];
      offer(tissue.Vertices[nearest], tissue.Voxels[i], (tissue.Voxels[i] - current.Points[nearest]).norm());
    }
  }
  for (const Tissue& tissue : this->Tissues) // then vertices far from every voxel
  {
    const Snapshot& current = *tissue.Current;
    for (std::size_t i = 0; i < tissue.Vertices.size(); ++i)
    {
      const PointId v = tissue.Vertices[i];
      const int voxel = current.NearestVoxel[i];
      const double d = (tissue.Voxels[voxel] - current.Points[i]).norm();
      if (d < search[v])
      {
        offer(v, tissue.Voxels[voxel], d);
      }
    }
  }
}

double FidelityGuard::Measure(const Tissue& tissue, Snapshot& at) const
{
  // The farthest of `from` from `to`, keeping each one's nearest, over the pairs whose vertex
  // counts; a max reduction is exact: the same for any thread count.
  auto counted = [&](int vertex) { return tissue.Counted.empty() || tissue.Counted[vertex]; };
  auto farthest = [this](const std::vector<Eigen::Vector3d>& from, const PointGrid& to,
                    const std::vector<Eigen::Vector3d>& toPoints, std::vector<int>& nearest,
                    const std::function<bool(std::size_t, int)>& counts) {
    nearest = to.NearestAnyOfAll(from, this->Threads);
    double worst = 0.0;
    for (std::size_t i = 0; i < from.size(); ++i)
      if (nearest[i] >= 0 && counts(i, nearest[i]))
        worst = std::max(worst, (toPoints[nearest[i]] - from[i]).norm());
    return worst;
  };
  return std::max(farthest(at.Points, *tissue.Grid, tissue.Voxels, at.NearestVoxel,
                    [&](std::size_t vertex, int) { return counted(int(vertex)); }),
    farthest(tissue.Voxels, *at.Grid, at.Points, at.NearestVertex,
      [&](std::size_t, int vertex) { return counted(vertex); }));
}
} // namespace cbc3d
