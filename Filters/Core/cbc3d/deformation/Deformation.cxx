#include "cbc3d/deformation/Deformation.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/TetGeometry.h"
#include "cbc3d/deformation/ElasticStep.h"
#include "cbc3d/deformation/FidelityGuard.h"
#include "cbc3d/deformation/GuardedStep.h"
#include "cbc3d/deformation/InteriorSmoothing.h"
#include "cbc3d/deformation/StopRequests.h"
#include "cbc3d/deformation/Matcher.h"
#include "cbc3d/deformation/SurfaceSources.h"
#include "cbc3d/deformation/TissueVolumes.h"
#include "cbc3d/quality/Quality.h"
#include "cbc3d/sampling/SurfacePoints.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>
#include <functional>
#include <limits>
#include <memory>
#include <cmath>
#include <sstream>
#include <utility>

namespace cbc3d
{
namespace
{
// Rigid fits per iteration at most (each matches again): an offset of a few voxels needs
// about ten.
constexpr int MaximumRigidRounds = 20;

// The paper's registration iterations over a set-up mesh: matching, a rigid fit, steering the
// farthest vertices, an elastic step with the goals as penalty springs, guarded.
class Registration
{
public:
  Registration(const TetMesh& mesh, const SurfaceSources& sources, const Matcher& matcher,
    FidelityGuard& fidelity, BlockMatrix&& stiffness,
    const DeformationParams& params, const StepBounds& bounds, double negligibleMove)
    : Mesh(mesh)
    , Sources(sources)
    , Match(matcher)
    , Fidelity(fidelity)
    , Params(params)
    , Bounds(bounds)
    , NegligibleMove(negligibleMove)
    , Smoothing(mesh.Tets, mesh.Points.size(), bounds.EdgeLimits.empty() ? nullptr : &bounds.EdgeLimits,
        params.NumberOfThreads)
    , Reach(mesh.Points.size())
    , Search(mesh.Points.size())
    , Interior(mesh.Points.size(), 1)
    , Elastic(std::move(stiffness))
  {
    // How far from the image a vertex may lie before it is steered, and how far it looks.
    for (std::size_t p = 0; p < mesh.Points.size(); ++p)
    {
      this->Reach[p] = 0.5 * sources.LocalSize[p];
      this->Search[p] = 3.0 * sources.LocalSize[p];
    }
    for (const PointId p : sources.Points)
    {
      this->Interior[p] = 0;
    }
    for (std::size_t p = 0; p < params.FixedPoints.size(); ++p)
    {
      this->Interior[p] = this->Interior[p] && !params.FixedPoints[p];
    }
  }

  /// One iteration from the points at x (moved in place when a step is made): the sources'
  /// mean goal distance in `moved`, the vertices held back in `held`.
  StepOutcome Iterate(std::vector<Eigen::Vector3d>& x, double done, StopRequests& stops, double& moved,
    std::size_t& held)
  {
    // Goals, approached by at most one element size; unmatched sources keep their place.
    std::vector<Eigen::Vector3d> goals;
    std::vector<char> matched;
    this->Match.Match(x, goals, matched);
    if (this->Params.RigidAlignment && this->Params.FixedPoints.empty() &&
      !this->AlignRigidly(x, goals, matched, stops, done))
    {
      return StepOutcome::Aborted;
    }
    this->SteerFarthest(goals, matched);
    Eigen::VectorXd rhs, springs;
    moved = this->SpringLoads(x, goals, matched, rhs, springs);
    // (Stopped(done) first: the solve's KeepGoing reports this iteration's fraction.)
    if (stops.Stopped(done) || !this->Elastic.Solve(springs, rhs, this->Params.NumberOfThreads, stops.KeepGoing))
    {
      return StepOutcome::Aborted;
    }
    std::vector<Eigen::Vector3d> trial;
    std::vector<double> share;
    const StepOutcome outcome = GuardedStep(this->Mesh, x,
      [&](std::size_t p) { return this->IsFixed(p) ? Eigen::Vector3d::Zero() : this->Elastic.Displacement(p); },
      this->Bounds,
      this->Params.NumberOfThreads, this->Fidelity, stops.KeepGoing, trial, share);
    if (outcome == StepOutcome::Aborted || stops.Stopped())
    {
      return StepOutcome::Aborted;
    }
    held = static_cast<std::size_t>(std::count_if(share.begin(), share.end(), [](double f) { return f < 1.0; }));
    if (outcome == StepOutcome::Made)
    {
      x.swap(trial);
      this->MakeRoom(x, share);
      this->Fidelity.Accept(x, stops.KeepGoing);
    }
    return outcome;
  }

private:
  bool IsFixed(std::size_t p) const { return !this->Params.FixedPoints.empty() && this->Params.FixedPoints[p]; }

  // The rigid part of the match first (rotation and translation, Umeyama's least squares): it
  // moves the mesh without straining a tet, where the elastic step alone would have its
  // strained tets held back by the quality guard. Matching again after each move and fitting
  // again (an ICP loop) until the move is negligible, so that a mesh offset from its image
  // follows it whole before any elastic step bends it toward half-found matches. False when
  // stopped.
  bool AlignRigidly(std::vector<Eigen::Vector3d>& x, std::vector<Eigen::Vector3d>& goals,
    std::vector<char>& matched, StopRequests& stops, double done)
  {
    const std::int64_t sourceCount = static_cast<std::int64_t>(this->Sources.Points.size());
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
          from.col(i) = x[this->Sources.Points[s]];
          to.col(i++) = goals[s];
        }
      }
      const Eigen::Isometry3d rigid(Eigen::umeyama(from, to, false));
      const std::int64_t pointCount = static_cast<std::int64_t>(x.size());
      std::vector<Eigen::Vector3d> trial(pointCount);
      double largestMove = 0.0;
#pragma omp parallel for schedule(static) reduction(max : largestMove) num_threads(ThreadCount(this->Params.NumberOfThreads))
      for (std::int64_t p = 0; p < pointCount; ++p)
      {
        trial[p] = rigid * x[p];
        largestMove = std::max(largestMove, (trial[p] - x[p]).norm());
      }
      if (largestMove < this->NegligibleMove ||
        !BadTets(this->Mesh, trial, this->Bounds, this->Params.NumberOfThreads).empty() ||
        !this->Fidelity.AcceptIfNoneGrows(trial, stops.KeepGoing))
      {
        break;
      }
      x.swap(trial);
      this->Placement = rigid * this->Placement;
      this->Match.Match(x, goals, matched);
      if (stops.Stopped(done))
      {
        return false;
      }
    }
    return true;
  }

  // Then the vertices that set a tissue's Hausdorff distance, wherever the matches left them
  // (after the rigid move, which they do not steer): a vertex farther than half its element
  // size from the boundary voxels of one of its tissues, or nearest to a boundary voxel
  // farther than that, heads for that voxel.
  void SteerFarthest(std::vector<Eigen::Vector3d>& goals, std::vector<char>& matched) const
  {
    std::vector<Eigen::Vector3d> steeredGoal;
    std::vector<char> steered;
    this->Fidelity.Steer(this->Reach, this->Search, steeredGoal, steered);
    for (std::size_t s = 0; s < this->Sources.Points.size(); ++s)
    {
      if (steered[this->Sources.Points[s]])
      {
        goals[s] = steeredGoal[this->Sources.Points[s]];
        matched[s] = 1;
      }
    }
  }

  // Each source's spring (Penalty times its own diagonal stiffness) and the load pulling it to
  // its goal; returns the sum of the distances to the goals.
  double SpringLoads(const std::vector<Eigen::Vector3d>& x, const std::vector<Eigen::Vector3d>& goals,
    const std::vector<char>& matched, Eigen::VectorXd& rhs, Eigen::VectorXd& springs) const
  {
    rhs = Eigen::VectorXd::Zero(this->Elastic.Size());
    springs = Eigen::VectorXd::Zero(this->Elastic.Size());
    const std::int64_t sourceCount = static_cast<std::int64_t>(this->Sources.Points.size());
    double moved = 0.0;
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : moved) num_threads(ThreadCount(this->Params.NumberOfThreads))
    for (std::int64_t s = 0; s < sourceCount; ++s)
    {
      const PointId p = this->Sources.Points[s];
      const double size = this->Sources.LocalSize[p];
      for (int c = 0; c < 3; ++c)
      {
        springs[3 * p + c] = this->Params.Penalty * this->Elastic.DiagonalStiffness(3 * p + c);
      }
      if (!matched[s] || this->IsFixed(p))
      {
        continue; // held in place by its spring, rather than drift with its neighbours
      }
      // Never farther than one element size from where the vertex started (after the rigid
      // moves), so vertices cannot drift along a boundary over the iterations.
      const Eigen::Vector3d start = this->Placement * this->Mesh.Points[p];
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
    // A fixed point is tied by a spring so stiff that its neighbours solve as if it were
    // clamped (its own step is then dropped).
    for (std::size_t p = 0; p < this->Params.FixedPoints.size(); ++p)
    {
      for (int c = 0; this->Params.FixedPoints[p] && c < 3; ++c)
      {
        springs[3 * p + c] = 1e6 * this->Elastic.DiagonalStiffness(Eigen::Index(3 * p + c));
      }
    }
    return moved;
  }

  // Interior vertices around the held ones make room for them on the next step.
  void MakeRoom(std::vector<Eigen::Vector3d>& x, const std::vector<double>& share) const
  {
    std::vector<char> held(x.size());
    for (std::size_t p = 0; p < x.size(); ++p)
    {
      held[p] = share[p] < 1.0;
    }
    std::vector<char> movable = this->Smoothing.SharingATetWith(held, this->Params.NumberOfThreads);
    for (std::size_t p = 0; p < x.size(); ++p)
    {
      movable[p] = movable[p] && this->Interior[p];
    }
    this->Smoothing.Smooth(x, movable, 2, this->Params.NumberOfThreads);
  }

  const TetMesh& Mesh;
  const SurfaceSources& Sources;
  const Matcher& Match;
  FidelityGuard& Fidelity;
  const DeformationParams& Params;
  const StepBounds& Bounds;    // what no step may do to a tet
  const double NegligibleMove; // a rigid fit that moves no point farther ends its loop
  const InteriorSmoothing Smoothing;
  std::vector<double> Reach, Search; // per point: when it is steered, and how far it looks
  std::vector<char> Interior;        // per point: not a source
  ElasticStep Elastic;
  Eigen::Isometry3d Placement = Eigen::Isometry3d::Identity(); // the rigid moves so far
};

// A rigid fit that moves no point farther than this ends its loop: 1% of the smallest surface
// element. In the mesh's mm, not the voxels' (it was 1% of a voxel): the brain upsampled 4x per
// axis, the same mesh, ran 31 rounds over 5 iterations where the brain ran 12, its first 18 in
// a row moving 0.04 down to 0.002 mm, each measuring all its boundary voxels again.
double NegligibleRigidMove(const SurfaceSources& sources)
{
  double smallestElement = std::numeric_limits<double>::infinity();
  for (const PointId p : sources.Points)
  {
    smallestElement = std::min(smallestElement, sources.LocalSize[p]);
  }
  return 0.01 * smallestElement;
}

// The image, the mesh and the parameters' ranges, or an error naming what is wrong.
Status ValidateInputs(const LabelImage& image, const TetMesh& mesh, const DeformationParams& params)
{
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
  if (!params.FixedPoints.empty() && params.FixedPoints.size() != mesh.Points.size())
  {
    return Status::Error("deformation needs one fixed-point flag per point, or none");
  }
  if (params.Iterations < 0 || !(params.Penalty > 0.0) ||
    !(params.MinimumDihedralAngle >= 0.0 && params.MinimumDihedralAngle < 60.0))
  {
    return Status::Error("deformation needs iterations >= 0, a positive penalty and a minimum "
                         "dihedral angle from 0 to 60 degrees");
  }
  return Status::Ok();
}

// The registration iterations, until `iterations` are done, a step would spoil tets, or the
// surface stops approaching the image; false when stopped by the user.
bool RunIterations(Registration& registration, int iterations, std::size_t sourceCount,
  std::vector<Eigen::Vector3d>& x, StopRequests& stops, DeformationResult& result)
{
  // A huge iteration count ends once the surface stops approaching the image: its vertices
  // keep jittering by up to a voxel, but their mean distance to their goals levels off.
  constexpr int Patience = 5; // iterations without a 1% gain; 5 iterations or fewer never stop
  double closest = std::numeric_limits<double>::infinity();
  int withoutGain = 0;
  for (int iteration = 0; iteration < iterations; ++iteration)
  {
    double moved = 0.0;
    std::size_t held = 0;
    const StepOutcome outcome =
      registration.Iterate(x, 0.1 + 0.9 * double(iteration) / iterations, stops, moved, held);
    if (outcome == StepOutcome::Aborted)
    {
      return false;
    }
    if (outcome == StepOutcome::Spoilt)
    {
      result.StopReason = "a step could not be made without spoiling tets; the previous mesh is kept";
      break;
    }
    ++result.Iterations;
    result.MeanStep.push_back(moved / double(sourceCount));
    result.HeldVertices.push_back(held);
    if (stops.Stopped(0.1 + 0.9 * double(iteration + 1) / iterations))
    {
      return false;
    }
    withoutGain = result.MeanStep.back() < 0.99 * closest ? 0 : withoutGain + 1;
    closest = std::min(closest, result.MeanStep.back());
    if (withoutGain == Patience)
    {
      result.StopReason = "settled after " + std::to_string(result.Iterations) +
        " iterations: the last " + std::to_string(Patience) + " brought the surface no closer to the image";
      break;
    }
  }
  return true;
}

// Each tissue's volume to keep: its voxels', moved by the tissue's VolumeOffsets.
std::map<std::int32_t, double> VolumeTargets(const LabelImage& image, const DeformationParams& params)
{
  std::map<std::int32_t, double> targets = TissueImageVolumes(image, params.NumberOfThreads);
  for (const auto& [tissue, offset] : params.VolumeOffsets)
  {
    const auto target = targets.find(tissue); // (background labels have none)
    if (target != targets.end())
    {
      target->second += offset;
    }
  }
  return targets;
}
} // namespace

Status DeformPoints(const LabelImage& image, const TetMesh& mesh, const DeformationParams& params,
  std::vector<Eigen::Vector3d>& x, DeformationResult& result, const Progress& progress)
{
  x = mesh.Points;
  result = DeformationResult();
  result.Displacement.assign(mesh.Points.size(), Eigen::Vector3d::Zero());
  const Status valid = ValidateInputs(image, mesh, params);
  if (!valid.IsOk())
  {
    return valid;
  }
  if (params.Iterations == 0 || mesh.Tets.empty())
  {
    result.StopReason = "no deformation asked (0 iterations)";
    return Status::Ok();
  }
  const int threads = params.NumberOfThreads;
  // The starting mesh must itself satisfy the bound, or no step could ever be checked against it.
  const StepBounds bounds = MakeStepBounds(mesh,
    std::min(params.MinimumDihedralAngle / RadiansToDegrees, SmallestAngleMargin(mesh, threads)), params.MaximumEdge);
  StopRequests stops(progress);
  if (stops.Stopped(0.01))
  {
    return Status::Aborted();
  }
  // The tets and labels stay as they are: one list of the surfaces' faces serves every stage
  // below (each looks at those alone).
  const std::vector<MeshFace> faces = SurfaceFaces(mesh, threads);
  const SurfaceSources sources = FindSurfaceSources(mesh, faces);
  if (stops.Stopped(0.02))
  {
    return Status::Aborted();
  }
  // The tissues' boundary voxels, found once for the targets and the fidelity guard.
  const TissueVoxels boundary = WithinWindow(image, TissueBoundaryVoxels(image, threads), params.VoxelWindow);
  const std::vector<BoundaryTarget> targets = FindBoundaryTargets(image, boundary, params.Pattern, params.Placement);
  if (stops.Stopped(0.04))
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
  // Boundary voxels are dense: a grid of about a voxel per cell keeps each query short
  // (measured on the brain: 3% fewer instructions in all than cells of two voxels).
  FidelityGuard fidelity(
    image, boundary, mesh, faces, image.Spacing.maxCoeff(), threads, stops.KeepGoing, params.FixedPoints);
  if (stops.Stopped(0.07))
  {
    return Status::Aborted();
  }
  BlockMatrix stiffness = AssembleStiffness(mesh, params.Materials,
    params.DefaultMaterial, threads, [&](double fraction) { return !stops.Stopped(0.07 + 0.03 * fraction); });
  if (stops.Stopped(0.1))
  {
    return Status::Aborted();
  }
  {
    // (In a scope of its own: the stiffness and the smoothing's lists are freed before the
    // volumes build theirs, where the run's peak was.)
    Registration registration(
      mesh, sources, matcher, fidelity, std::move(stiffness), params, bounds, NegligibleRigidMove(sources));
    if (!RunIterations(registration, params.Iterations, sources.Points.size(), x, stops, result))
    {
      return Status::Aborted();
    }
  }
  if (params.KeepVolumes && result.Iterations > 0)
  {
    // Half a voxel per round at most: the shortfalls left are well under a voxel deep.
    const TissueVolumeKeeper volumes(mesh, faces, VolumeTargets(image, params), 0.5 * image.Spacing.minCoeff());
    std::vector<PointId> moving;
    for (const PointId p : sources.Points)
    {
      if (params.FixedPoints.empty() || !params.FixedPoints[p])
      {
        moving.push_back(p);
      }
    }
    if (RestoreTissueVolumes(volumes, mesh, moving, x, bounds, threads, fidelity, stops.KeepGoing) ==
      StepOutcome::Aborted)
    {
      return Status::Aborted();
    }
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

Status DeformMesh(const LabelImage& image, const TetMesh& mesh, const DeformationParams& params,
  TetMesh& out, DeformationResult& result, const Progress& progress)
{
  std::vector<Eigen::Vector3d> moved;
  const Status status = DeformPoints(image, mesh, params, moved, result, progress);
  out.Points = std::move(moved);
  out.Tets = mesh.Tets;
  out.Labels = mesh.Labels;
  return status;
}
} // namespace cbc3d
