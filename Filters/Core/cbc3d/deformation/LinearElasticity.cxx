#include "cbc3d/deformation/LinearElasticity.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/PointTets.h"

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

namespace
{
// Point p's neighbours, itself included, each once, in `list` (unsorted). `seen` is the
// thread's own, one entry per point: q is listed for p when seen[q] == p. (Each neighbour comes
// from six tets or so: marking, not sorting all the tets' corners, finds each once.)
void ListNeighbours(const TetMesh& mesh, const PointTets& around, std::int64_t p, std::vector<std::int64_t>& seen,
  std::vector<PointId>& list)
{
  list.assign(1, static_cast<PointId>(p)); // a point in no tet still has its own block
  seen[p] = p;
  for (std::int64_t i = around.Start[p]; i < around.Start[p + 1]; ++i)
    for (const PointId q : mesh.Tets[around.Tets[i]])
      if (seen[q] != p)
      {
        seen[q] = p;
        list.push_back(q);
      }
}

// Calls visit(p, list) for every point p, on the threads, with `list` its neighbours
// (ListNeighbours; the visit may reorder them).
template <typename Visit>
void ForEachNeighbourList(const TetMesh& mesh, const PointTets& around, int threads, const Visit& visit)
{
  const std::int64_t n = static_cast<std::int64_t>(mesh.Points.size());
  RegionErrors errors;
#pragma omp parallel num_threads(threads)
  {
    std::vector<std::int64_t> seen;
    std::vector<PointId> list;
    errors.Run([&] { seen.assign(n, -1); }); // every thread meets the loop below, failed or not
#pragma omp for schedule(dynamic, 1024)
    for (std::int64_t p = 0; p < n; ++p)
      errors.Run([&] {
          ListNeighbours(mesh, around, p, seen, list);
          visit(p, list);
        });
  }
  errors.Rethrow();
}

// The blocks' pattern (point p's row holds a block for p and for every point sharing an edge
// with it: counted, then filled, ascending) and zero values.
void SetUpBlocks(const TetMesh& mesh, const PointTets& around, int threads, BlockMatrix& stiffness)
{
  const std::int64_t n = static_cast<std::int64_t>(mesh.Points.size());
  stiffness.RowStart.assign(n + 1, 0);
  ForEachNeighbourList(mesh, around, threads, [&](std::int64_t p, std::vector<PointId>& list) {
    stiffness.RowStart[p + 1] = static_cast<std::int64_t>(list.size());
  });
  for (std::int64_t p = 0; p < n; ++p)
    stiffness.RowStart[p + 1] += stiffness.RowStart[p];
  stiffness.Columns.resize(stiffness.Blocks());
  stiffness.Values.resize(9 * stiffness.Blocks());
  ForEachNeighbourList(mesh, around, threads, [&](std::int64_t p, std::vector<PointId>& list) {
    std::sort(list.begin(), list.end());
    std::copy(list.begin(), list.end(), stiffness.Columns.begin() + stiffness.RowStart[p]);
    std::fill(stiffness.Values.begin() + 9 * stiffness.RowStart[p], stiffness.Values.begin() + 9 * stiffness.RowStart[p + 1], 0.0);
  });
}

// The points of tets begin..end-1, each once (`batchOf[p]`: the last batch p was listed for).
std::vector<PointId> PointsOfBatch(const TetMesh& mesh, std::int64_t begin, std::int64_t end,
  std::vector<std::int64_t>& batchOf)
{
  std::vector<PointId> points;
  for (std::int64_t t = begin; t < end; ++t)
    for (const PointId p : mesh.Tets[t])
      if (batchOf[p] != begin)
      {
        batchOf[p] = begin;
        points.push_back(p);
      }
  return points;
}

// Adds the matrices of tets begin..end-1 (local[t - begin]) into the blocks of their points
// (`points`: only those, not every point of the mesh for every batch).
// Each point's blocks are written by one thread, its tets taken in ascending order
// (`next[p]`: p's first tet not added yet), so every sum runs in tet order, as a serial
// loop over the tets would add it: the same matrix for any thread count.
void AddTetMatrices(const TetMesh& mesh, const PointTets& around,
  const std::vector<Eigen::Matrix<double, 12, 12>>& local, std::int64_t begin, std::int64_t end,
  const std::vector<PointId>& points, std::vector<std::int64_t>& next, int threads, BlockMatrix& stiffness)
{
  const std::int64_t n = static_cast<std::int64_t>(points.size());
#pragma omp parallel for schedule(dynamic, 256) num_threads(threads)
  for (std::int64_t i = 0; i < n; ++i)
  {
    const PointId p = points[i];
    const auto first = stiffness.Columns.begin() + stiffness.RowStart[p];
    const auto last = stiffness.Columns.begin() + stiffness.RowStart[p + 1];
    for (; next[p] < around.Start[p + 1] && around.Tets[next[p]] < end; ++next[p])
    {
      const std::int64_t t = around.Tets[next[p]];
      const Tet& tet = mesh.Tets[t];
      const int b = static_cast<int>(std::find(tet.begin(), tet.end(), p) - tet.begin()); // p's corner
      for (int a = 0; a < 4; ++a) // the other point's corner
      {
        const std::int64_t k = std::lower_bound(first, last, tet[a]) - stiffness.Columns.begin();
        double* block = stiffness.Values.data() + 9 * k;
        for (int c = 0; c < 3; ++c)
          for (int r = 0; r < 3; ++r)
            block[3 * c + r] += local[t - begin](3 * a + r, 3 * b + c);
      }
    }
  }
}
} // namespace

BlockMatrix AssembleStiffness(const TetMesh& mesh,
  const std::map<std::int32_t, Material>& materials, const Material& fallback, int numberOfThreads,
  const Progress& progress)
{
  // The pattern first, then each tet adds its 12x12 matrix into its points' blocks. (Building
  // it from 144 triplets per tet needed 16 bytes per triplet: 1.5 GB on a 650k-tet mesh.) That
  // takes seconds on such a mesh: a stop request is looked for between the steps and the
  // batches.
  BlockMatrix stiffness;
  const int threads = ThreadCount(numberOfThreads);
  const PointTets around(mesh.Tets, mesh.Points.size());
  if (!KeepGoing(progress, 0.1))
  {
    return BlockMatrix();
  }
  SetUpBlocks(mesh, around, threads, stiffness);
  if (!KeepGoing(progress, 0.2))
  {
    return BlockMatrix();
  }

  // Tets in batches (their 12x12 matrices take 1152 bytes each), computed in parallel.
  const std::int64_t tetCount = static_cast<std::int64_t>(mesh.Tets.size());
  constexpr std::int64_t batch = 4096;
  std::vector<Eigen::Matrix<double, 12, 12>> local(static_cast<std::size_t>(std::min(batch, tetCount)));
  std::vector<std::int64_t> next(around.Start.begin(), around.Start.end() - 1);
  std::vector<std::int64_t> batchOf(mesh.Points.size(), -1);
  for (std::int64_t begin = 0; begin < tetCount; begin += batch)
  {
    if (!KeepGoing(progress, 0.3 + 0.7 * double(begin) / double(tetCount)))
    {
      return BlockMatrix();
    }
    const std::int64_t end = std::min(tetCount, begin + batch);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t t = begin; t < end; ++t)
    {
      const auto found = materials.find(mesh.Labels[t]);
      local[t - begin] = TetStiffness(mesh, mesh.Tets[t], found == materials.end() ? fallback : found->second);
    }
    const std::vector<PointId> points = PointsOfBatch(mesh, begin, end, batchOf);
    AddTetMatrices(mesh, around, local, begin, end, points, next, threads, stiffness);
  }
  return stiffness;
}
} // namespace cbc3d
