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
// Lamé's constants of an isotropic material.
struct Lame
{
  double Lambda, Mu;
  explicit Lame(const Material& m)
    : Lambda(m.YoungModulus * m.PoissonRatio / ((1.0 + m.PoissonRatio) * (1.0 - 2.0 * m.PoissonRatio)))
    , Mu(m.YoungModulus / (2.0 * (1.0 + m.PoissonRatio)))
  {
  }
};

// The gradients of a tet's four shape functions (its rows), and its volume.
double ShapeGradients(const TetMesh& mesh, const Tet& tet, Eigen::Matrix<double, 4, 3>& gradient)
{
  Eigen::Matrix3d edges;
  for (int v = 0; v < 3; ++v)
  {
    edges.col(v) = mesh.Points[tet[v + 1]] - mesh.Points[tet[0]];
  }
  // Rows of the inverse edge matrix; N0's is minus their sum.
  const Eigen::Matrix3d inverse = edges.inverse();
  gradient.bottomRows<3>() = inverse;
  gradient.row(0) = -inverse.colwise().sum();
  return std::abs(edges.determinant()) / 6.0;
}

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

// Calls visit(p, list) for every point p in [begin, end), on the threads, with `list` its
// neighbours (ListNeighbours; the visit may reorder them). `seen` holds each thread's marks
// (filled on first use): calls that visit no point twice may share them, so the chunks of one
// pass mark a point's array once, not once a chunk.
template <typename Visit>
void ForEachNeighbourList(const TetMesh& mesh, const PointTets& around, std::int64_t begin, std::int64_t end,
  int threads, std::vector<std::vector<std::int64_t>>& seen, const Visit& visit)
{
  const std::int64_t n = static_cast<std::int64_t>(mesh.Points.size());
  RegionErrors errors;
#pragma omp parallel num_threads(threads)
  {
    std::vector<std::int64_t>& marks = seen[ThreadId()];
    std::vector<PointId> list;
    errors.Run([&] {
      if (marks.empty())
        marks.assign(n, -1);
    }); // every thread meets the loop below, failed or not
#pragma omp for schedule(dynamic, 1024)
    for (std::int64_t p = begin; p < end; ++p)
      errors.Run([&] {
          ListNeighbours(mesh, around, p, marks, list);
          visit(p, list);
        });
  }
  errors.Rethrow();
}

// Point p's row: K(3p + c, 3q + r) = sum over the tets around p (in ascending order) of
// V (lambda g_p,c g_q,r + mu g_p,r g_q,c + mu [c = r] g_p . g_q), the gradients g of the tet's
// shape functions at p's corner and q's: the blocks of V B^T D B for linear tets, summed in
// double and stored as BlockMatrix keeps them.
void AssembleRow(const TetMesh& mesh, const PointTets& around, std::int64_t p,
  const std::map<std::int32_t, Material>& materials, const Material& fallback, std::vector<double>& sums,
  BlockMatrix& stiffness)
{
  const std::int64_t first = stiffness.RowStart[p], count = stiffness.RowStart[p + 1] - first;
  const std::int32_t* columns = stiffness.Columns.data() + first;
  sums.assign(9 * count, 0.0);
  Eigen::Matrix<double, 4, 3> g;
  for (std::int64_t i = around.Start[p]; i < around.Start[p + 1]; ++i)
  {
    const Tet& tet = mesh.Tets[around.Tets[i]];
    const auto found = materials.find(mesh.Labels[around.Tets[i]]);
    const Lame lame(found == materials.end() ? fallback : found->second);
    const double volume = ShapeGradients(mesh, tet, g);
    const int b = static_cast<int>(std::find(tet.begin(), tet.end(), p) - tet.begin()); // p's corner
    for (int a = 0; a < 4; ++a)
    {
      double* block = sums.data() + 9 * (std::lower_bound(columns, columns + count, tet[a]) - columns);
      const double dot = g.row(a).dot(g.row(b));
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
          block[3 * c + r] += volume * (lame.Lambda * g(b, c) * g(a, r) + lame.Mu * g(b, r) * g(a, c) +
            (c == r ? lame.Mu * dot : 0.0));
    }
  }
  for (std::int64_t k = 0; k < count; ++k)
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r)
      {
        const bool diagonal = columns[k] == p && c == r;
        stiffness.Values[9 * (first + k) + 3 * c + r] = diagonal ? 0.0f : static_cast<float>(sums[9 * k + 3 * c + r]);
        if (diagonal)
          stiffness.Diagonal[3 * p + c] = sums[9 * k + 3 * c + r];
      }
}
} // namespace

BlockMatrix AssembleStiffness(const TetMesh& mesh,
  const std::map<std::int32_t, Material>& materials, const Material& fallback, int numberOfThreads,
  const Progress& progress)
{
  // The pattern first (point p's row holds a block for p and for every point sharing an edge
  // with it: counted), then each row from its tets, in chunks of points: that takes seconds on
  // large meshes, and a stop request is looked for between the chunks. (Building the matrix
  // from 144 triplets per tet needed 16 bytes per triplet: 1.5 GB on a 650k-tet mesh.)
  const int threads = ThreadCount(numberOfThreads);
  const PointTets around(mesh.Tets, mesh.Points.size(), threads);
  const std::int64_t n = static_cast<std::int64_t>(mesh.Points.size());
  BlockMatrix stiffness;
  stiffness.RowStart.assign(n + 1, 0);
  std::vector<std::vector<std::int64_t>> seen(threads);
  ForEachNeighbourList(mesh, around, 0, n, threads, seen, [&](std::int64_t p, std::vector<PointId>& list) {
    stiffness.RowStart[p + 1] = static_cast<std::int64_t>(list.size());
  });
  for (std::int64_t p = 0; p < n; ++p)
    stiffness.RowStart[p + 1] += stiffness.RowStart[p];
  stiffness.Columns.resize(stiffness.Blocks());
  stiffness.Values.resize(9 * stiffness.Blocks());
  stiffness.Diagonal.resize(3 * n);
  for (std::vector<std::int64_t>& marks : seen)
    marks.clear(); // the rows' pass visits every point again
  const std::int64_t chunk = std::max<std::int64_t>(65536, n / 16);
  for (std::int64_t begin = 0; begin < n; begin += chunk)
  {
    if (!KeepGoing(progress, 0.1 + 0.9 * double(begin) / double(n)))
    {
      return BlockMatrix();
    }
    ForEachNeighbourList(mesh, around, begin, std::min(n, begin + chunk), threads, seen,
      [&](std::int64_t p, std::vector<PointId>& list) {
        thread_local std::vector<double> sums; // the row's blocks, summed in double
        std::sort(list.begin(), list.end());
        std::copy(list.begin(), list.end(), stiffness.Columns.begin() + stiffness.RowStart[p]);
        AssembleRow(mesh, around, p, materials, fallback, sums, stiffness);
      });
  }
  return stiffness;
}
} // namespace cbc3d
