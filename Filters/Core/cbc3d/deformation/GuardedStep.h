#ifndef cbc3d_GuardedStep_h
#define cbc3d_GuardedStep_h

#include "cbc3d/base/TetMesh.h"
#include "cbc3d/deformation/FidelityGuard.h"
#include "cbc3d/deformation/TissueVolumes.h"

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <vector>

namespace cbc3d
{
/// The tets that points at `x` would invert or push past the angle bound (radians). With
/// `moved` (one flag per point), only tets with a moved point are checked: the others are as
/// they were, and every accepted position satisfies the bound.
std::vector<std::int64_t> BadTets(const TetMesh& mesh, const std::vector<Eigen::Vector3d>& x,
  double minimumRadians, int threads, const std::vector<char>* moved = nullptr);

enum class StepOutcome
{
  Made,
  Spoilt, // no step could be found that spoils no tet
  Aborted
};

/// Tries x + share * step(p); shortens it at the vertices of tets it would invert or push past
/// the angle bound (by half each round, then not at all), and holds the vertices that would make
/// a tissue's Hausdorff distance grow, until no tet is spoilt. `trial` and `share` hold the step
/// made. `step` is called from `threads` threads at once.
StepOutcome GuardedStep(const TetMesh& mesh, const std::vector<Eigen::Vector3d>& x,
  const std::function<Eigen::Vector3d(std::size_t)>& step, double bound, int threads,
  FidelityGuard& fidelity, const std::function<bool()>& keepGoing,
  std::vector<Eigen::Vector3d>& trial, std::vector<double>& share);

/// Moves the surface and interface points straight along their normals until each tissue holds
/// its target volume (rounds of first-order offsets, each a guarded step): what the elastic
/// steps left of the shortfall, where springs and held vertices fell short of the goals. A
/// tissue that a round moved only part of the way asks for more in the next (VolumeAims).
StepOutcome RestoreTissueVolumes(const TissueVolumeKeeper& volumes, const TetMesh& mesh,
  const std::vector<PointId>& surface, std::vector<Eigen::Vector3d>& x, double bound, int threads,
  FidelityGuard& fidelity, const std::function<bool()>& keepGoing);
} // namespace cbc3d

#endif
