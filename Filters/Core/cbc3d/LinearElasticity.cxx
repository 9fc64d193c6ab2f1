#include "cbc3d/LinearElasticity.h"

#include "cbc3d/Parallel.h"
#include "cbc3d/PointTets.h"

#include <Eigen/Dense>

#include <algorithm>
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
// V B^T D B of one 4-node tet, rows and columns in (point, axis) order.
Eigen::Matrix<double, 12, 12> TetStiffness(const TetMesh& mesh, const Tet& tet, const Material& material)
{
  const Eigen::Matrix<double, 6, 6> d = Elasticity(material);
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
  return std::abs(volume) * b.transpose() * d * b;
}
} // namespace

Eigen::SparseMatrix<double> AssembleStiffness(const TetMesh& mesh,
  const std::map<std::int32_t, Material>& materials, const Material& fallback, int numberOfThreads,
  const Progress& progress)
{
  // The pattern first: point p's row holds a 3x3 block for p and for every point sharing an
  // edge with it. Then each tet adds its 12x12 matrix into those blocks. (Building it from
  // 144 triplets per tet needed 16 bytes per triplet: 1.5 GB on a 650k-tet mesh.) That takes
  // seconds on such a mesh: a stop request is looked for between the steps and the batches.
  // Every return names this one matrix, so it is built in place (Eigen 3.4's sparse matrix has
  // no move constructor: any other return would copy it).
  Eigen::SparseMatrix<double> stiffness;
  const std::int64_t n = static_cast<std::int64_t>(mesh.Points.size());
  // Point p's neighbours (itself included), ascending, are neighbours[rowStart[p]..rowStart[p+1]).
  std::vector<std::int64_t> rowStart(n + 1, 0); // in blocks
  std::vector<PointId> neighbours;
  {
    const PointTets around(mesh.Tets, static_cast<std::size_t>(n));
    if (!KeepGoing(progress, 0.1))
    {
      return stiffness;
    }
    neighbours.reserve(16 * static_cast<std::size_t>(n)); // a lattice point has 14 and itself
    std::vector<PointId> list;
    for (std::int64_t p = 0; p < n; ++p)
    {
      list.clear();
      for (std::int64_t i = around.Start[p]; i < around.Start[p + 1]; ++i)
        for (const PointId q : mesh.Tets[around.Tets[i]])
          list.push_back(q);
      list.push_back(p); // a point in no tet still has its own block
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
      neighbours.insert(neighbours.end(), list.begin(), list.end());
      rowStart[p + 1] = static_cast<std::int64_t>(neighbours.size());
    }
  }
  auto neighboursOf = [&](PointId p) {
    return std::make_pair(neighbours.begin() + rowStart[p], neighbours.begin() + rowStart[p + 1]);
  };
  if (!KeepGoing(progress, 0.2))
  {
    return stiffness;
  }
  // Column-major storage of a symmetric matrix: column 3p+c lists the rows of p's blocks.
  // Written straight into the matrix's arrays: copying them in took most of a second.
  const std::int64_t blocks = rowStart[n];
  const int dofs = static_cast<int>(3 * n);
  stiffness.resize(dofs, dofs);
  stiffness.resizeNonZeros(static_cast<Eigen::Index>(9 * blocks));
  int* outer = stiffness.outerIndexPtr();
  int* inner = stiffness.innerIndexPtr();
  double* values = stiffness.valuePtr();
  std::fill(values, values + 9 * blocks, 0.0);
  for (std::int64_t p = 0; p < n; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      const std::int64_t column = 3 * p + c;
      const std::int64_t first = 9 * rowStart[p] + 3 * (rowStart[p + 1] - rowStart[p]) * c;
      outer[column] = static_cast<int>(first);
      std::int64_t k = first;
      for (auto [q, last] = neighboursOf(p); q != last; ++q)
        for (int r = 0; r < 3; ++r)
          inner[k++] = static_cast<int>(3 * *q + r);
    }
  }
  outer[3 * n] = static_cast<int>(9 * blocks);

  // Tets in parallel compute their matrices; the additions run in tet order, so the sums are
  // the same for any thread count.
  const std::int64_t tetCount = static_cast<std::int64_t>(mesh.Tets.size());
  constexpr std::int64_t batch = 8192;
  std::vector<Eigen::Matrix<double, 12, 12>> local(static_cast<std::size_t>(std::min(batch, tetCount)));
  for (std::int64_t begin = 0; begin < tetCount; begin += batch)
  {
    if (!KeepGoing(progress, 0.3 + 0.7 * double(begin) / double(tetCount)))
    {
      return stiffness;
    }
    const std::int64_t end = std::min(tetCount, begin + batch);
#pragma omp parallel for schedule(static) num_threads(ThreadCount(numberOfThreads))
    for (std::int64_t t = begin; t < end; ++t)
    {
      const auto found = materials.find(mesh.Labels[t]);
      local[t - begin] = TetStiffness(mesh, mesh.Tets[t], found == materials.end() ? fallback : found->second);
    }
    for (std::int64_t t = begin; t < end; ++t)
    {
      const Tet& tet = mesh.Tets[t];
      for (int b = 0; b < 4; ++b) // column point
      {
        const PointId p = tet[b];
        const auto [first, last] = neighboursOf(p);
        for (int a = 0; a < 4; ++a) // row point
        {
          const std::int64_t slot = std::lower_bound(first, last, tet[a]) - first;
          for (int c = 0; c < 3; ++c)
          {
            double* column = values + outer[3 * p + c] + 3 * slot;
            for (int r = 0; r < 3; ++r)
            {
              column[r] += local[t - begin](3 * a + r, 3 * b + c);
            }
          }
        }
      }
    }
  }
  return stiffness;
}
} // namespace cbc3d
