#include "cbc3d/Deformation.h"

#include "cbc3d/FidelityGuard.h"
#include "cbc3d/GuardedStep.h"
#include "cbc3d/InteriorSmoothing.h"
#include "cbc3d/Matcher.h"
#include "cbc3d/Parallel.h"
#include "cbc3d/Quality.h"
#include "cbc3d/SurfaceSources.h"
#include "cbc3d/TetGeometry.h"
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
// Rigid fits per iteration at most (each matches again): an offset of a few voxels needs
// about ten.
constexpr int MaximumRigidRounds = 20;
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
  const SurfaceSources sources = FindSurfaceSources(mesh);
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
    RestoreTissueVolumes(volumes, mesh, sources.Points, x, bound, threads, fidelity, keepGoing) == StepOutcome::Aborted)
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
