#include "cbc3d/Deformation.h"

#include "cbc3d/InteriorSmoothing.h"
#include "cbc3d/MeshFaces.h"
#include "cbc3d/Parallel.h"
#include "cbc3d/PointGrid.h"
#include "cbc3d/Quality.h"
#include "cbc3d/SurfacePoints.h"
#include "cbc3d/TetGeometry.h"
#include "cbc3d/TetTopology.h"
#include "cbc3d/TissueVolumes.h"

#include <Eigen/Geometry>
#include <Eigen/IterativeLinearSolvers>

#include <algorithm>
#include <atomic>
#include <functional>
#include <memory>
#include <cmath>
#include <sstream>

namespace cbc3d
{
namespace
{
// Surface and interface vertices with their label-sets, and every vertex's element size.
struct Sources
{
  std::vector<PointId> Points;
  std::vector<LabelSet> Labels;
  std::vector<double> LocalSize; // per mesh point: mean length of the edges at it
};

Sources FindSources(const TetMesh& mesh)
{
  const std::size_t n = mesh.Points.size();
  std::vector<char> onSurface(n, 0), outer(n, 0);
  for (const MeshFace& face : FindMeshFaces(mesh))
  {
    const bool boundary = face.TetCount == 1;
    const bool interface = face.TetCount == 2 && mesh.Labels[face.Tets[0]] != mesh.Labels[face.Tets[1]];
    for (const PointId p : face.Points)
    {
      onSurface[p] |= boundary || interface;
      outer[p] |= boundary;
    }
  }
  std::vector<LabelSet> labels(n);
  std::vector<double> length(n, 0.0);
  std::vector<int> edges(n, 0);
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const Tet& tet = mesh.Tets[t];
    for (const PointId p : tet)
    {
      if (onSurface[p] && std::find(labels[p].begin(), labels[p].end(), mesh.Labels[t]) == labels[p].end())
      {
        labels[p].push_back(mesh.Labels[t]);
      }
    }
    for (const auto& e : TetEdges)
    {
      const double l = (mesh.Points[tet[e[0]]] - mesh.Points[tet[e[1]]]).norm();
      length[tet[e[0]]] += l;
      length[tet[e[1]]] += l;
      ++edges[tet[e[0]]];
      ++edges[tet[e[1]]];
    }
  }
  Sources sources;
  sources.LocalSize.resize(n);
  for (std::size_t p = 0; p < n; ++p)
  {
    sources.LocalSize[p] = edges[p] ? length[p] / edges[p] : 0.0;
    if (onSurface[p])
    {
      if (outer[p])
      {
        labels[p].push_back(OutsideLabel);
      }
      std::sort(labels[p].begin(), labels[p].end());
      sources.Points.push_back(static_cast<PointId>(p));
      sources.Labels.push_back(labels[p]);
    }
  }
  return sources;
}

// The label-sets a source may match: those holding all its labels (its own, or more where a
// third tissue touches, as on the speckled border of a k-means image); failing that (no target
// has them), the sets of two or more of its labels that targets have, such as the two-tissue
// interfaces meeting at a triple line.
std::vector<int> AcceptedSets(const LabelSet& source, const std::map<LabelSet, int>& present)
{
  std::vector<int> accepted;
  for (const auto& [set, id] : present)
  {
    if (std::includes(set.begin(), set.end(), source.begin(), source.end()))
    {
      accepted.push_back(id);
    }
  }
  if (!accepted.empty())
  {
    return accepted;
  }
  for (const auto& [set, id] : present)
  {
    if (set.size() >= 2 && std::includes(source.begin(), source.end(), set.begin(), set.end()))
    {
      accepted.push_back(id);
    }
  }
  return accepted;
}

// The registration's correspondences: each source's goal, from the targets whose label-sets
// it accepts.
class Matcher
{
public:
  Matcher(const Sources& sources, const std::vector<BoundaryTarget>& targets, int threads)
    : SourceList(sources)
    , Threads(threads)
  {
    std::map<LabelSet, int> present; // label-sets as small integers
    for (const BoundaryTarget& t : targets)
    {
      this->TargetSet.push_back(present.emplace(t.Labels, int(present.size())).first->second);
      this->TargetPoints.push_back(t.Position);
    }
    for (std::size_t s = 0; s < sources.Points.size(); ++s)
    {
      this->Accepted.push_back(AcceptedSets(sources.Labels[s], present));
      this->LargestSize = std::max(this->LargestSize, sources.LocalSize[sources.Points[s]]);
    }
    this->Cell = std::max(2.0 * this->LargestSize, 1e-6);
    this->TargetGrid = std::make_unique<PointGrid>(this->TargetPoints, this->Cell);
  }

  /// Goals for the sources at positions x: each source's nearest target of an accepted
  /// label-set within twice its element size, averaged with the targets whose nearest source
  /// it is (so that parts of the image boundary far from every vertex pull the surface too).
  /// Sources with neither are not `matched`.
  void Match(const std::vector<Eigen::Vector3d>& x, std::vector<Eigen::Vector3d>& goals,
    std::vector<char>& matched) const
  {
    const Sources& sources = this->SourceList;
    const std::int64_t sourceCount = static_cast<std::int64_t>(sources.Points.size());
    const std::int64_t targetCount = static_cast<std::int64_t>(this->TargetPoints.size());
    std::vector<Eigen::Vector3d> sourcePoints(sourceCount);
    for (std::int64_t s = 0; s < sourceCount; ++s)
    {
      sourcePoints[s] = x[sources.Points[s]];
    }
    const PointGrid sourceGrid(sourcePoints, this->Cell);
    std::vector<int> nearestSource(targetCount);
#pragma omp parallel for schedule(dynamic, 256) num_threads(ThreadCount(this->Threads))
    for (std::int64_t t = 0; t < targetCount; ++t)
    {
      nearestSource[t] = sourceGrid.Nearest(this->TargetPoints[t], 2.0 * this->LargestSize, [&](int s) {
        return this->Accepts(s, t) &&
          (this->TargetPoints[t] - sourcePoints[s]).norm() <= 2.0 * sources.LocalSize[sources.Points[s]];
      });
    }
    std::vector<Eigen::Vector3d> goalSum(sourceCount, Eigen::Vector3d::Zero());
    std::vector<int> goalCount(sourceCount, 0);
    for (std::int64_t t = 0; t < targetCount; ++t)
    {
      if (nearestSource[t] >= 0)
      {
        goalSum[nearestSource[t]] += this->TargetPoints[t];
        ++goalCount[nearestSource[t]];
      }
    }
    goals.assign(sourceCount, Eigen::Vector3d::Zero());
    matched.assign(sourceCount, 0);
#pragma omp parallel for schedule(dynamic, 64) num_threads(ThreadCount(this->Threads))
    for (std::int64_t s = 0; s < sourceCount; ++s)
    {
      const PointId p = sources.Points[s];
      const int match = this->TargetGrid->Nearest(
        x[p], 2.0 * sources.LocalSize[p], [&](int t) { return this->Accepts(s, t); });
      if (match < 0 && goalCount[s] == 0)
      {
        continue; // no target near
      }
      const Eigen::Vector3d averaged = goalCount[s] > 0 ? Eigen::Vector3d(goalSum[s] / goalCount[s]) : Eigen::Vector3d::Zero();
      goals[s] = match < 0 ? averaged
        : goalCount[s] > 0 ? Eigen::Vector3d(0.5 * (averaged + this->TargetPoints[match]))
                           : this->TargetPoints[match];
      matched[s] = 1;
    }
  }

private:
  bool Accepts(std::int64_t source, std::int64_t target) const
  {
    const auto& sets = this->Accepted[source];
    return std::find(sets.begin(), sets.end(), this->TargetSet[target]) != sets.end();
  }

  const Sources& SourceList;
  int Threads;
  std::vector<Eigen::Vector3d> TargetPoints;
  std::vector<int> TargetSet;             // per target, the number of its label-set
  std::vector<std::vector<int>> Accepted; // per source, the label-set numbers it accepts
  double LargestSize = 0.0;               // the largest element size at a source
  double Cell = 0.0;                      // grid cell: twice that
  std::unique_ptr<PointGrid> TargetGrid;
};

// Rigid fits per iteration at most (each matches again): an offset of a few voxels needs
// about ten.
constexpr int MaximumRigidRounds = 20;

// Tets that a move would invert or push past the angle bound.
std::vector<std::int64_t> BadTets(const TetMesh& mesh, const std::vector<Eigen::Vector3d>& x,
  double minimumRadians, int threads)
{
  const std::int64_t count = static_cast<std::int64_t>(mesh.Tets.size());
  std::vector<char> bad(count, 0);
#pragma omp parallel for schedule(static) num_threads(ThreadCount(threads))
  for (std::int64_t t = 0; t < count; ++t)
  {
    const Tet& tet = mesh.Tets[t];
    if (!(SignedVolume(x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]]) > 0.0))
    {
      bad[t] = 1;
      continue;
    }
    bad[t] = !DihedralAnglesWithin(x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]], minimumRadians);
  }
  std::vector<std::int64_t> result;
  for (std::int64_t t = 0; t < count; ++t)
  {
    if (bad[t])
    {
      result.push_back(t);
    }
  }
  return result;
}
// Keeps each tissue's Hausdorff distance from growing: the distance between the tissue's
// surface vertices and its boundary voxel centres (the measure vtkCBC3DMeshQuality reports).
// It keeps each tissue's vertices at the last accepted positions, with a grid over them.
class FidelityGuard
{
public:
  /// Measures every tissue's distance, asking `keepGoing` before each; when it says stop, the
  /// guard is left unfinished.
  FidelityGuard(const LabelImage& image, const TetMesh& mesh, double cell,
    int threads, const std::function<bool()>& keepGoing)
    : Cell(cell)
    , Threads(threads)
  {
    const auto vertices = TissueSurfaceVertices(mesh);
    const auto voxels = TissueBoundaryVoxels(image, threads);
    for (const auto& [label, ids] : vertices)
    {
      const auto found = voxels.find(label);
      if (found != voxels.end())
      {
        Tissue tissue{ label, ids };
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
      tissue.Grid = std::make_unique<PointGrid>(tissue.Voxels, cell);
      tissue.Current = std::make_unique<Snapshot>(tissue.Vertices, mesh.Points, cell);
      tissue.Hausdorff = this->Measure(tissue, *tissue.Current);
    }
  }

  /// Holds back (share 0) the vertices whose step from the accepted positions to `trial` would
  /// push a tissue's Hausdorff distance past its current value: vertices that would end farther
  /// from the tissue's boundary voxels, and the former nearest vertices of boundary voxels that
  /// would be left farther from the mesh. Returns how many vertices it held. Asks `keepGoing`
  /// before each tissue; when it says stop, returns at once (the count then means nothing).
  std::size_t Hold(const std::vector<Eigen::Vector3d>& trial, std::vector<double>& share,
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
      const Snapshot after(tissue.Vertices, trial, this->Cell);
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

  /// Takes these positions, and their distances as the new limits, unless some tissue's would
  /// grow; returns whether it took them. Asks `keepGoing` before each tissue (false when
  /// stopped).
  bool AcceptIfNoneGrows(const std::vector<Eigen::Vector3d>& points, const std::function<bool()>& keepGoing)
  {
    std::vector<std::unique_ptr<Snapshot>> snapshots;
    std::vector<double> measured;
    for (const Tissue& tissue : this->Tissues)
    {
      if (!keepGoing())
      {
        return false;
      }
      snapshots.push_back(std::make_unique<Snapshot>(tissue.Vertices, points, this->Cell));
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

  /// Takes these positions, and their distances as the new limits where smaller. Asks
  /// `keepGoing` before each tissue; when it says stop, returns at once.
  void Accept(const std::vector<Eigen::Vector3d>& points, const std::function<bool()>& keepGoing)
  {
    for (Tissue& tissue : this->Tissues)
    {
      if (!keepGoing())
      {
        return;
      }
      tissue.Current = std::make_unique<Snapshot>(tissue.Vertices, points, this->Cell);
      tissue.Hausdorff = std::min(tissue.Hausdorff, this->Measure(tissue, *tissue.Current));
    }
  }

  /// Goals for the vertices that set a tissue's Hausdorff distance, at the accepted positions:
  /// of the boundary voxels whose nearest vertex of the tissue a point is, and the point's
  /// nearest boundary voxel of each of its tissues (when within `search[point]`), the farthest,
  /// if farther than `reach[point]`; the goal is that voxel's centre, with either target
  /// placement: these vertices set the Hausdorff distance, which measures to centres, so with
  /// face targets the bulk of the surface keeps the tissue's volume while its worst points do
  /// not drift half a voxel off that measure (brain, paper's settings, face: 3.58 -> 3.41 mm).
  /// `steered[point]` is 0 where there is none.
  void Steer(const std::vector<double>& reach, const std::vector<double>& search,
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

private:
  // A tissue's surface vertices at some positions, with a grid over them (the grid refers to
  // the positions, so a snapshot stays where it was made: it is neither copied nor moved).
  struct Snapshot
  {
    Snapshot(const std::vector<PointId>& ids, const std::vector<Eigen::Vector3d>& points, double cell)
    {
      for (const PointId v : ids)
      {
        this->Points.push_back(points[v]);
      }
      this->Grid = std::make_unique<PointGrid>(this->Points, cell);
    }
    Snapshot(const Snapshot&) = delete;
    Snapshot& operator=(const Snapshot&) = delete;

    std::vector<Eigen::Vector3d> Points;
    std::unique_ptr<PointGrid> Grid;
    std::vector<int> NearestVertex; // per boundary voxel of the tissue, once measured
    std::vector<int> NearestVoxel;  // per vertex, once measured
  };

  struct Tissue
  {
    std::int32_t Label;
    std::vector<PointId> Vertices;
    std::vector<Eigen::Vector3d> Voxels; // boundary voxel centres, which the distance measures to
    double Hausdorff = 0.0;
    std::unique_ptr<PointGrid> Grid;        // over Voxels
    std::unique_ptr<Snapshot> Current;      // the vertices at the accepted positions
  };

  // Two-sided distance between the tissue's boundary voxels and its vertices at `at`; keeps
  // each voxel's nearest vertex and each vertex's nearest voxel in `at` (Steer reads them).
  double Measure(const Tissue& tissue, Snapshot& at) const
  {
    // The farthest of `from` from `to`, keeping each one's nearest; a max reduction is exact:
    // the same for any thread count.
    auto farthest = [this](const std::vector<Eigen::Vector3d>& from, const PointGrid& to,
                      const std::vector<Eigen::Vector3d>& toPoints, std::vector<int>& nearest) {
      double worst = 0.0;
      const std::int64_t count = static_cast<std::int64_t>(from.size());
      nearest.resize(count);
#pragma omp parallel for schedule(dynamic, 256) reduction(max : worst) num_threads(ThreadCount(this->Threads))
      for (std::int64_t i = 0; i < count; ++i)
      {
        nearest[i] = to.NearestAny(from[i]);
        worst = std::max(worst, nearest[i] < 0 ? 0.0 : (toPoints[nearest[i]] - from[i]).norm());
      }
      return worst;
    };
    return std::max(farthest(at.Points, *tissue.Grid, tissue.Voxels, at.NearestVoxel),
      farthest(tissue.Voxels, *at.Grid, at.Points, at.NearestVertex));
  }

  double Cell;
  int Threads;
  std::vector<Tissue> Tissues;
};

enum class StepOutcome
{
  Made,
  Spoilt, // no step could be found that spoils no tet
  Aborted
};

// Tries x + share * step(p); shortens it at the vertices of tets it would invert or push past
// the angle bound (by half each round, then not at all), and holds the vertices that would make
// a tissue's Hausdorff distance grow, until no tet is spoilt. `trial` and `share` hold the step
// made.
StepOutcome GuardedStep(const TetMesh& mesh, const std::vector<Eigen::Vector3d>& x,
  const std::function<Eigen::Vector3d(std::size_t)>& step, double bound, int threads,
  FidelityGuard& fidelity, const std::function<bool()>& keepGoing,
  std::vector<Eigen::Vector3d>& trial, std::vector<double>& share)
{
  trial.resize(x.size());
  share.assign(x.size(), 1.0);
  for (int round = 0; round < 50; ++round)
  {
    if (!keepGoing())
    {
      return StepOutcome::Aborted;
    }
    for (std::size_t p = 0; p < x.size(); ++p)
    {
      trial[p] = x[p] + share[p] * step(p);
    }
    const std::vector<std::int64_t> bad = BadTets(mesh, trial, bound, threads);
    if (bad.empty())
    {
      if (fidelity.Hold(trial, share, keepGoing) == 0)
      {
        return keepGoing() ? StepOutcome::Made : StepOutcome::Aborted;
      }
      continue; // held for fidelity: try again with those vertices in place
    }
    // Once per round for each vertex, however many spoilt tets it has.
    std::vector<char> spoilt(x.size(), 0);
    for (const std::int64_t t : bad)
    {
      for (const PointId p : mesh.Tets[t])
      {
        spoilt[p] = 1;
      }
    }
    for (std::size_t p = 0; p < x.size(); ++p)
    {
      if (spoilt[p])
      {
        share[p] = share[p] > 1.0 / 16.0 ? 0.5 * share[p] : 0.0;
      }
    }
  }
  return StepOutcome::Spoilt;
}

// Moves the surface and interface points straight along their normals until each tissue holds
// its target volume (rounds of first-order offsets, each step guarded like a deformation step):
// what the elastic steps left of the shortfall, where springs and held vertices fell short of
// the offset goals.
StepOutcome KeepVolumes(const TissueVolumeKeeper& volumes, const TetMesh& mesh,
  const std::vector<PointId>& surface, std::vector<Eigen::Vector3d>& x, double bound, int threads,
  FidelityGuard& fidelity, const std::function<bool()>& keepGoing)
{
  std::vector<char> moving(x.size(), 0);
  for (const PointId p : surface)
  {
    moving[p] = 1;
  }
  std::vector<Eigen::Vector3d> trial;
  std::vector<double> share;
  // Each round's step is shortened where tets would spoil, so a few rounds may be needed.
  for (int round = 0; round < 8 && volumes.LargestRelativeShortfall(x) > 1e-3; ++round)
  {
    std::vector<Eigen::Vector3d> goals = x;
    volumes.OffsetGoals(goals, moving);
    const StepOutcome outcome = GuardedStep(mesh, x, [&](std::size_t p) { return Eigen::Vector3d(goals[p] - x[p]); },
      bound, threads, fidelity, keepGoing, trial, share);
    if (outcome != StepOutcome::Made)
    {
      return outcome;
    }
    x.swap(trial);
    fidelity.Accept(x, keepGoing);
  }
  return StepOutcome::Made;
}
} // namespace

Status DeformMesh(const LabelImage& image, const TetMesh& mesh, const DeformationParams& params,
  TetMesh& out, DeformationResult& result, const Progress& progress)
{
  out = mesh;
  result = DeformationResult();
  result.Displacement.assign(mesh.Points.size(), Eigen::Vector3d::Zero());
  const Status valid = ValidateLabelImage(image);
  if (!valid.IsOk())
  {
    return valid;
  }
  const Status validMesh = ValidateTetMesh(mesh);
  if (!validMesh.IsOk())
  {
    return Status::Error("the mesh to deform is not valid: " + validMesh.GetMessage());
  }
  if (params.Iterations < 0 || !(params.Penalty > 0.0) ||
    !(params.MinimumDihedralAngle >= 0.0 && params.MinimumDihedralAngle < 60.0))
  {
    return Status::Error("deformation needs iterations >= 0, a positive penalty and a minimum "
                         "dihedral angle from 0 to 60 degrees");
  }
  if (params.Iterations == 0 || mesh.Tets.empty())
  {
    result.StopReason = "no deformation asked (0 iterations)";
    return Status::Ok();
  }
  const int threads = params.NumberOfThreads;
  const double minimumRadians = params.MinimumDihedralAngle / RadiansToDegrees;
  // The starting mesh must itself satisfy the bound, or no step could ever be checked against it.
  const double startingMinimum = [&] {
    double smallest = M_PI;
    for (const Tet& tet : mesh.Tets)
      for (const double a : DihedralAngles(mesh.Points[tet[0]], mesh.Points[tet[1]], mesh.Points[tet[2]], mesh.Points[tet[3]]))
        smallest = std::min({ smallest, a, M_PI - a });
    return smallest;
  }();
  const double bound = std::min(minimumRadians, startingMinimum);

  // Setting up and every iteration take seconds on large meshes: look for a stop request
  // between the steps, and inside the longest ones through `keepGoing` (reporting the
  // fraction last reached). A stop, once seen, is kept: a step cut short is never used.
  bool stop = false;
  double reached = 0.0;
  auto stopped = [&](double fraction) {
    reached = fraction;
    stop = stop || !KeepGoing(progress, fraction);
    return stop;
  };
  const std::function<bool()> keepGoing = [&] { return !stopped(reached); };
  if (stopped(0.01))
  {
    return Status::Aborted();
  }
  const Sources sources = FindSources(mesh);
  if (stopped(0.02))
  {
    return Status::Aborted();
  }
  const std::vector<BoundaryTarget> targets = FindBoundaryTargets(image, params.Pattern, params.Placement);
  if (stopped(0.04))
  {
    return Status::Aborted();
  }
  result.Sources = sources.Points.size();
  result.Targets = targets.size();
  if (sources.Points.empty() || targets.empty())
  {
    result.StopReason = "nothing to register (no surface vertex or no boundary voxel)";
    return Status::Ok();
  }
  const Matcher matcher(sources, targets, threads);
  // Half a voxel per round at most: the shortfalls left are well under a voxel deep.
  const TissueVolumeKeeper volumes(mesh, params.KeepVolumes ? TissueImageVolumes(image) : std::map<std::int32_t, double>(),
    0.5 * image.Spacing.minCoeff());
  const std::int64_t sourceCount = static_cast<std::int64_t>(sources.Points.size());
  // Boundary voxels are dense: a grid of a few voxels per cell keeps each query short.
  FidelityGuard fidelity(image, mesh, 2.0 * image.Spacing.maxCoeff(), threads, keepGoing);
  if (stopped(0.07))
  {
    return Status::Aborted();
  }
  const Eigen::SparseMatrix<double> stiffness = AssembleStiffness(mesh, params.Materials,
    params.DefaultMaterial, threads, [&](double fraction) { return !stopped(0.07 + 0.03 * fraction); });
  if (stopped(0.1))
  {
    return Status::Aborted();
  }
  // (K + P) du = P d: K the stiffness, P the springs tying each matched source to its goal.
  // Conjugate gradients with a diagonal preconditioner, warm-started from the previous step.
  // (Measured on the brain and the k-means head: twice as fast as an incomplete-Cholesky
  // preconditioner, in less memory and to the same result; a sparse direct factorisation was
  // 20 times slower: 3-D meshes fill in badly.)
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
    Eigen::DiagonalPreconditioner<double>>
    cg;
  cg.setTolerance(1e-6);
  cg.setMaxIterations(50); // per call: the solve runs in chunks so that a stop is seen soon
  std::vector<Eigen::Vector3d>& x = out.Points;
  const InteriorSmoothing smoothing(mesh.Tets, x.size());
  // How far from the image a vertex may lie before it is steered, and how far it looks.
  std::vector<double> reach(x.size()), search(x.size());
  for (std::size_t p = 0; p < x.size(); ++p)
  {
    reach[p] = 0.5 * sources.LocalSize[p];
    search[p] = 3.0 * sources.LocalSize[p];
  }
  std::vector<char> interior(x.size(), 1);
  for (const PointId p : sources.Points)
  {
    interior[p] = 0;
  }
  Eigen::VectorXd du = Eigen::VectorXd::Zero(stiffness.rows());
  Eigen::Isometry3d placement = Eigen::Isometry3d::Identity(); // the rigid moves so far
  const double negligibleMove = 0.01 * image.Spacing.minCoeff(); // a rigid fit that ends its loop
  for (int iteration = 0; iteration < params.Iterations; ++iteration)
  {
    const double done = 0.1 + 0.9 * double(iteration) / params.Iterations;
    // Goals, approached by at most one element size; unmatched sources keep their place.
    std::vector<Eigen::Vector3d> goals;
    std::vector<char> matched;
    matcher.Match(x, goals, matched);

    // The rigid part of the match first (rotation and translation, Umeyama's least squares):
    // it moves the mesh without straining a tet, where the elastic step alone would have its
    // strained tets held back by the quality guard. Matching again after each move and fitting
    // again (an ICP loop) until the move is negligible, so that a mesh offset from its image
    // follows it whole before any elastic step bends it toward half-found matches.
    if (params.RigidAlignment)
    {
      for (int round = 0; round < MaximumRigidRounds; ++round)
      {
        const std::int64_t count = std::count(matched.begin(), matched.end(), 1);
        if (count < 4)
        {
          break;
        }
        Eigen::Matrix3Xd from(3, count), to(3, count);
        for (std::int64_t s = 0, i = 0; s < sourceCount; ++s)
        {
          if (matched[s])
          {
            from.col(i) = x[sources.Points[s]];
            to.col(i++) = goals[s];
          }
        }
        const Eigen::Isometry3d rigid(Eigen::umeyama(from, to, false));
        std::vector<Eigen::Vector3d> trial(x.size());
        double largestMove = 0.0;
        for (std::size_t p = 0; p < x.size(); ++p)
        {
          trial[p] = rigid * x[p];
          largestMove = std::max(largestMove, (trial[p] - x[p]).norm());
        }
        if (largestMove < negligibleMove || !BadTets(out, trial, bound, threads).empty() ||
          !fidelity.AcceptIfNoneGrows(trial, keepGoing))
        {
          break;
        }
        x.swap(trial);
        placement = rigid * placement;
        matcher.Match(x, goals, matched);
        if (stopped(done))
        {
          return Status::Aborted();
        }
      }
    }

    // Then the vertices that set a tissue's Hausdorff distance, wherever the matches left them
    // (after the rigid move, which they do not steer): a vertex farther than half its element
    // size from the boundary voxels of one of its tissues, or nearest to a boundary voxel
    // farther than that, heads for that voxel.
    std::vector<Eigen::Vector3d> steeredGoal;
    std::vector<char> steered;
    fidelity.Steer(reach, search, steeredGoal, steered);
    for (std::int64_t s = 0; s < sourceCount; ++s)
    {
      if (steered[sources.Points[s]])
      {
        goals[s] = steeredGoal[sources.Points[s]];
        matched[s] = 1;
      }
    }

    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(stiffness.rows());
    Eigen::VectorXd springs = Eigen::VectorXd::Zero(stiffness.rows());
    double moved = 0.0;
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : moved) num_threads(ThreadCount(threads))
    for (std::int64_t s = 0; s < sourceCount; ++s)
    {
      const PointId p = sources.Points[s];
      const double size = sources.LocalSize[p];
      for (int c = 0; c < 3; ++c)
      {
        springs[3 * p + c] = params.Penalty * stiffness.coeff(3 * p + c, 3 * p + c);
      }
      if (!matched[s])
      {
        continue; // held in place by its spring, rather than drift with its neighbours
      }
      // Never farther than one element size from where the vertex started (after the rigid
      // moves), so vertices cannot drift along a boundary over the iterations.
      const Eigen::Vector3d start = placement * mesh.Points[p];
      Eigen::Vector3d goal = goals[s];
      if ((goal - start).norm() > size)
      {
        goal = start + (goal - start) * (size / (goal - start).norm());
      }
      const Eigen::Vector3d d = goal - x[p];
      moved += d.norm();
      for (int c = 0; c < 3; ++c)
      {
        rhs[3 * p + c] = springs[3 * p + c] * d[c];
      }
    }
    if (stopped(done))
    {
      return Status::Aborted();
    }
    // A faint anchor on every point keeps pieces of the mesh that no spring holds (a small
    // component with no match) in place, where the bare stiffness would let them float.
    Eigen::SparseMatrix<double> system = stiffness;
    for (int i = 0; i < system.rows(); ++i)
    {
      system.coeffRef(i, i) += springs[i] + 1e-6 * stiffness.coeff(i, i);
    }
    if (stopped(done))
    {
      return Status::Aborted();
    }
    cg.compute(system);
    for (int chunk = 0; chunk < 20; ++chunk)
    {
      du = cg.solveWithGuess(rhs, du);
      if (cg.info() == Eigen::Success)
      {
        break;
      }
      if (stopped(done))
      {
        return Status::Aborted();
      }
    }

    std::vector<Eigen::Vector3d> trial;
    std::vector<double> share;
    const StepOutcome outcome = GuardedStep(mesh, x, [&](std::size_t p) { return Eigen::Vector3d(du.segment<3>(3 * p)); },
      bound, threads, fidelity, keepGoing, trial, share);
    if (outcome == StepOutcome::Aborted || stop)
    {
      return Status::Aborted();
    }
    const std::size_t heldCount = static_cast<std::size_t>(
      std::count_if(share.begin(), share.end(), [](double f) { return f < 1.0; }));
    if (outcome == StepOutcome::Spoilt)
    {
      result.StopReason = "a step could not be made without spoiling tets; the previous mesh is kept";
      break;
    }
    x.swap(trial);
    {
      // Interior vertices around the held ones make room for them on the next step.
      std::vector<char> movable(x.size(), 0);
      for (const Tet& tet : mesh.Tets)
      {
        if (std::any_of(tet.begin(), tet.end(), [&](PointId p) { return share[p] < 1.0; }))
        {
          for (const PointId p : tet)
          {
            movable[p] = interior[p];
          }
        }
      }
      smoothing.Smooth(x, movable, 2);
    }
    fidelity.Accept(x, keepGoing);
    ++result.Iterations;
    result.MeanStep.push_back(moved / double(sourceCount));
    result.HeldVertices.push_back(heldCount);
    if (stopped(0.1 + 0.9 * double(iteration + 1) / params.Iterations))
    {
      return Status::Aborted();
    }
  }
  if (params.KeepVolumes && result.Iterations > 0 &&
    KeepVolumes(volumes, mesh, sources.Points, x, bound, threads, fidelity, keepGoing) == StepOutcome::Aborted)
  {
    return Status::Aborted();
  }
  for (std::size_t p = 0; p < x.size(); ++p)
  {
    result.Displacement[p] = x[p] - mesh.Points[p];
  }
  if (result.StopReason.empty())
  {
    std::ostringstream reason;
    reason << "done: " << result.Iterations << " iterations";
    result.StopReason = reason.str();
  }
  return Status::Ok();
}
} // namespace cbc3d
