#ifndef cbc3d_GuardedStep_h
#define cbc3d_GuardedStep_h

#include "cbc3d/base/EdgeLengthLimits.h"
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/deformation/FidelityGuard.h"
#include "cbc3d/deformation/TissueVolumes.h"

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <vector>

namespace cbc3d
{
/// What a step may not do to a tet: invert it, push a dihedral angle past MinimumRadians, or,
/// where EdgeLimits is not empty (one per tet, mm; 0 = none), make an edge longer than it.
struct StepBounds
{
  double MinimumRadians = 0.0;
  std::vector<double> EdgeLimits;
};

/// The smallest margin of any dihedral angle of the mesh from 0 or 180 degrees (radians); a
/// minimum, so the same for any thread count.
double SmallestAngleMargin(const TetMesh& mesh, int threads);

/// The bounds of a mesh's steps: the angle bound, and with any edge limit, each tissue tet's
/// limit or its longest edge at the start, whichever is longer (the starting mesh must satisfy
/// the bounds, or no step could ever be checked against them).
StepBounds MakeStepBounds(const TetMesh& mesh, double minimumRadians, const EdgeLengthLimits& limits);

/// The tets that points at `x` would invert, push past the angle bound or stretch past their
/// edge limit. With `moved` (one flag per point), only tets with a moved point are checked: the
/// others are as they were, and every accepted position satisfies the bounds.
std::vector<std::int64_t> BadTets(const TetMesh& mesh, const std::vector<Eigen::Vector3d>& x,
  const StepBounds& bounds, int threads, const std::vector<char>* moved = nullptr);

enum class StepOutcome
{
  Made,
  Spoilt, // no step could be found that spoils no tet
  Aborted
};

/// Tries x + share * step(p); shortens it at the vertices of tets it would invert or push past
/// the bounds (by half each round, then not at all), and holds the vertices that would make
/// a tissue's Hausdorff distance grow, until no tet is spoilt. `trial` and `share` hold the step
/// made. `step` is called from `threads` threads at once.
StepOutcome GuardedStep(const TetMesh& mesh, const std::vector<Eigen::Vector3d>& x,
  const std::function<Eigen::Vector3d(std::size_t)>& step, const StepBounds& bounds, int threads,
  FidelityGuard& fidelity, const std::function<bool()>& keepGoing,
  std::vector<Eigen::Vector3d>& trial, std::vector<double>& share);

/// Moves the surface and interface points straight along their normals until each tissue holds
/// its target volume (rounds of first-order offsets, each a guarded step): what the elastic
/// steps left of the shortfall, where springs and held vertices fell short of the goals. A
/// tissue that a round moved only part of the way asks for more in the next (VolumeAims).
StepOutcome RestoreTissueVolumes(const TissueVolumeKeeper& volumes, const TetMesh& mesh,
  const std::vector<PointId>& surface, std::vector<Eigen::Vector3d>& x, const StepBounds& bounds, int threads,
  FidelityGuard& fidelity, const std::function<bool()>& keepGoing);
} // namespace cbc3d

#endif
