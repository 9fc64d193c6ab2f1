#ifndef cbc3d_ElasticStep_h
#define cbc3d_ElasticStep_h

#include <Eigen/Core>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include <cstddef>
#include <functional>
#include <vector>

namespace cbc3d
{
/// The elastic step of a registration iteration: (K + P) du = P d, K the mesh's stiffness, P the
/// penalty springs that tie points to their goals, d the way to them. Each step writes only the
/// diagonal of the system again (the stiffness's own plus the springs) and solves by conjugate
/// gradients with a diagonal preconditioner, warm-started from the previous step.
class ElasticStep
{
public:
  /// Takes the stiffness over (it is left empty): 3 degrees of freedom per point.
  explicit ElasticStep(Eigen::SparseMatrix<double>& stiffness);

  /// The stiffness's own diagonal entry for degree of freedom i (3p + axis): springs are sized
  /// by it, so that a penalty means the same on small and large elements.
  double DiagonalStiffness(Eigen::Index i) const { return this->StiffnessDiagonal[i]; }

  /// Solves for springs P (per degree of freedom, 0 where none) and loads P d; false, with the
  /// step unfinished, when `keepGoing` (asked between chunks of iterations) says stop. Uses
  /// `threads` for the sparse products.
  bool Solve(const Eigen::VectorXd& springs, const Eigen::VectorXd& loads, int threads,
    const std::function<bool()>& keepGoing);

  /// Point p's displacement in the last step solved (zero before the first).
  Eigen::Vector3d Displacement(std::size_t p) const { return this->Du.segment<3>(3 * p); }

  Eigen::Index Size() const { return this->System.rows(); }

private:
  // Eigen's diagonal preconditioner, told the diagonal rather than searching every column of
  // the matrix for it at each solve (a serial scan: 1.5% of the brain's run on 2 threads). The
  // same inverses, so the same steps.
  class KnownDiagonal : public Eigen::DiagonalPreconditioner<double>
  {
  public:
    void Set(const std::vector<double*>& diagonal)
    {
      this->m_invdiag.resize(Eigen::Index(diagonal.size()));
      for (std::size_t i = 0; i < diagonal.size(); ++i)
        this->m_invdiag[Eigen::Index(i)] = *diagonal[i] != 0.0 ? 1.0 / *diagonal[i] : 1.0;
      this->m_isInitialized = true;
    }
    template <typename Matrix>
    KnownDiagonal& analyzePattern(const Matrix&) { return *this; }
    template <typename Matrix>
    KnownDiagonal& factorize(const Matrix&) { return *this; }
    template <typename Matrix>
    KnownDiagonal& compute(const Matrix&) { return *this; }
  };

  Eigen::SparseMatrix<double> System;  // the stiffness, its diagonal with the last springs added
  std::vector<double*> Diagonal;       // System's diagonal entries
  std::vector<double> StiffnessDiagonal;
  Eigen::VectorXd Du;                  // the last step (the next solve starts from it)
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper, KnownDiagonal> Solver;
};
} // namespace cbc3d

#endif
