#ifndef cbc3d_ElasticStep_h
#define cbc3d_ElasticStep_h

#include "cbc3d/deformation/BlockMatrix.h"

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <vector>

namespace cbc3d
{
/// The elastic step of a registration iteration: (K + P) du = P d, K the mesh's stiffness, P the
/// penalty springs that tie points to their goals, d the way to them. Each step writes only the
/// diagonal of the system again (the stiffness's own plus the springs) and solves by conjugate
/// gradients with a diagonal (Jacobi) preconditioner, warm-started from the previous step.
class ElasticStep
{
public:
  /// Takes the stiffness over: 3 degrees of freedom per point.
  explicit ElasticStep(BlockMatrix&& stiffness);

  /// The stiffness's own diagonal entry for degree of freedom i (3p + axis): springs are sized
  /// by it, so that a penalty means the same on small and large elements.
  double DiagonalStiffness(Eigen::Index i) const { return this->StiffnessDiagonal[i]; }

  /// Solves for springs P (per degree of freedom, 0 where none) and loads P d; false, with the
  /// step unfinished, when `keepGoing` (asked between chunks of iterations) says stop. Uses
  /// `threads` for the products.
  bool Solve(const Eigen::VectorXd& springs, const Eigen::VectorXd& loads, int threads,
    const std::function<bool()>& keepGoing);

  /// Point p's displacement in the last step solved (zero before the first).
  Eigen::Vector3d Displacement(std::size_t p) const { return this->Du.segment<3>(3 * p); }

  Eigen::Index Size() const { return this->System.Size(); }

private:
  // At most `iterations` conjugate-gradient iterations from Du toward the loads; true once the
  // residual is within the tolerance.
  bool Iterate(const Eigen::VectorXd& loads, int iterations, int threads);

  BlockMatrix System;                  // the stiffness, its diagonal with the last springs added
  std::vector<double> StiffnessDiagonal;
  Eigen::VectorXd InverseDiagonal;     // the preconditioner
  Eigen::VectorXd Du;                  // the last step (the next solve starts from it)
};
} // namespace cbc3d

#endif
