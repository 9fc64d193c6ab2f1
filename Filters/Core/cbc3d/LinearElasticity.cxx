#include "cbc3d/LinearElasticity.h"

#include "cbc3d/Parallel.h"

#include <Eigen/Dense>

#include <vector>

namespace cbc3d
{
namespace
{
Eigen::Matrix<double, 6, 6> Elasticity(const Material& m)
{
  const double e = m.YoungModulus;
  const double nu = m.PoissonRatio;
  const double scale = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
  Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
  d.topLeftCorner<3, 3>().setConstant(nu);
  d.topLeftCorner<3, 3>().diagonal().setConstant(1.0 - nu);
  d.bottomRightCorner<3, 3>().diagonal().setConstant(0.5 - nu);
  return scale * d;
}
} // namespace

Eigen::SparseMatrix<double> AssembleStiffness(const TetMesh& mesh,
  const std::map<std::int32_t, Material>& materials, const Material& fallback, int numberOfThreads)
{
  const std::int64_t tetCount = static_cast<std::int64_t>(mesh.Tets.size());
  std::vector<Eigen::Triplet<double>> triplets(static_cast<std::size_t>(tetCount) * 144);
#pragma omp parallel for schedule(static) num_threads(ThreadCount(numberOfThreads))
  for (std::int64_t t = 0; t < tetCount; ++t)
  {
    const Tet& tet = mesh.Tets[t];
    const auto found = materials.find(mesh.Labels[t]);
    const Eigen::Matrix<double, 6, 6> d = Elasticity(found == materials.end() ? fallback : found->second);
    Eigen::Matrix3d edges;
    for (int v = 0; v < 3; ++v)
    {
      edges.col(v) = mesh.Points[tet[v + 1]] - mesh.Points[tet[0]];
    }
    const double volume = edges.determinant() / 6.0;
    // Gradients of the shape functions: rows of the inverse edge matrix; N0's is minus their sum.
    const Eigen::Matrix3d inverse = edges.inverse();
    Eigen::Matrix<double, 4, 3> gradient;
    gradient.bottomRows<3>() = inverse;
    gradient.row(0) = -inverse.colwise().sum();
    Eigen::Matrix<double, 6, 12> b = Eigen::Matrix<double, 6, 12>::Zero();
    for (int v = 0; v < 4; ++v)
    {
      const double gx = gradient(v, 0), gy = gradient(v, 1), gz = gradient(v, 2);
      b(0, 3 * v) = gx;
      b(1, 3 * v + 1) = gy;
      b(2, 3 * v + 2) = gz;
      b(3, 3 * v) = gy; // engineering shear strains xy, yz, zx
      b(3, 3 * v + 1) = gx;
      b(4, 3 * v + 1) = gz;
      b(4, 3 * v + 2) = gy;
      b(5, 3 * v) = gz;
      b(5, 3 * v + 2) = gx;
    }
    const Eigen::Matrix<double, 12, 12> k = std::abs(volume) * b.transpose() * d * b;
    std::size_t slot = static_cast<std::size_t>(t) * 144;
    for (int r = 0; r < 12; ++r)
      for (int c = 0; c < 12; ++c)
        triplets[slot++] = Eigen::Triplet<double>(
          static_cast<int>(3 * tet[r / 3] + r % 3), static_cast<int>(3 * tet[c / 3] + c % 3), k(r, c));
  }
  const int dofs = static_cast<int>(3 * mesh.Points.size());
  Eigen::SparseMatrix<double> stiffness(dofs, dofs);
  stiffness.setFromTriplets(triplets.begin(), triplets.end());
  return stiffness;
}
} // namespace cbc3d
