#include "cbc3d/deformation/BlockMatrix.h"
#include "cbc3d/deformation/ElasticStep.h"
#include "cbc3d/deformation/LinearElasticity.h"

#include "TestMeshes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace
{
// The cube [0,2]^3 as six positive tets around its diagonal.
cbc3d::TetMesh Cube()
{
  cbc3d::TetMesh mesh;
  for (int c = 0; c < 8; ++c)
    mesh.Points.emplace_back(c & 1 ? 2 : 0, c & 2 ? 2 : 0, c & 4 ? 2 : 0);
  mesh.Tets = { { 0, 1, 3, 7 }, { 0, 3, 2, 7 }, { 0, 2, 6, 7 }, { 0, 6, 4, 7 }, { 0, 4, 5, 7 }, { 0, 5, 1, 7 } };
  mesh.Labels.assign(6, 1);
  return mesh;
}

Eigen::VectorXd Field(const cbc3d::TetMesh& mesh, const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& u)
{
  Eigen::VectorXd v(3 * mesh.Points.size());
  for (std::size_t p = 0; p < mesh.Points.size(); ++p)
    v.segment<3>(3 * p) = u(mesh.Points[p]);
  return v;
}

// K x by the block matrix's own product.
Eigen::VectorXd Times(const cbc3d::BlockMatrix& k, const Eigen::VectorXd& x, int threads = 1)
{
  Eigen::VectorXd y;
  k.Multiply(x, y, threads);
  return y;
}

// Every entry, one by one (small matrices only).
Eigen::MatrixXd Dense(const cbc3d::BlockMatrix& k)
{
  Eigen::MatrixXd dense(k.Size(), k.Size());
  for (Eigen::Index i = 0; i < k.Size(); ++i)
    for (Eigen::Index j = 0; j < k.Size(); ++j)
      dense(i, j) = k.Coefficient(i, j);
  return dense;
}
} // namespace

TEST(LinearElasticity, RigidMotionsCostNothingAndUniaxialStrainHasItsKnownEnergy)
{
  const cbc3d::TetMesh mesh = Cube();
  cbc3d::Material material{ 3.0, 0.25 };
  const cbc3d::BlockMatrix k = cbc3d::AssembleStiffness(mesh, {}, material, 2);
  ASSERT_EQ(k.Size(), 24);
  // Symmetric, and the product is the dense one's. (Entries off the diagonal are kept in single
  // precision: the known answers hold to a few parts in 10^7.)
  const Eigen::MatrixXd dense = Dense(k);
  constexpr double single = 1e-6;
  EXPECT_LT((dense - dense.transpose()).norm(), single * dense.norm());
  // A translation and an infinitesimal rotation: no force anywhere.
  const Eigen::VectorXd shift = Field(mesh, [](const Eigen::Vector3d&) { return Eigen::Vector3d(0.3, -1.0, 2.0); });
  EXPECT_LT(Times(k, shift).norm(), single * dense.norm() * shift.norm());
  const Eigen::Vector3d axis(0.2, 0.5, -0.3);
  const Eigen::VectorXd spin = Field(mesh, [&](const Eigen::Vector3d& x) { return Eigen::Vector3d(axis.cross(x)); });
  EXPECT_LT(Times(k, spin).norm(), single * dense.norm() * spin.norm());
  // u = (e x, 0, 0): strain energy 1/2 u.K.u = 1/2 e^2 (lambda + 2 mu) V, with V = 8.
  const double e = 0.01;
  const Eigen::VectorXd stretch = Field(mesh, [&](const Eigen::Vector3d& x) { return Eigen::Vector3d(e * x[0], 0, 0); });
  EXPECT_LT((Times(k, stretch) - dense * stretch).norm(), 1e-12);
  const double lambda = material.YoungModulus * material.PoissonRatio /
    ((1 + material.PoissonRatio) * (1 - 2 * material.PoissonRatio));
  const double mu = material.YoungModulus / (2 * (1 + material.PoissonRatio));
  const double energy = 0.5 * e * e * (lambda + 2 * mu) * 8.0;
  EXPECT_NEAR(0.5 * stretch.dot(Times(k, stretch)), energy, single * energy);
  // A stiffer tissue doubles its share.
  const cbc3d::BlockMatrix stiffer = cbc3d::AssembleStiffness(mesh, { { 1, { 6.0, 0.25 } } }, material, 1);
  EXPECT_NEAR(stretch.dot(Times(stiffer, stretch)), 2.0 * stretch.dot(Times(k, stretch)), single * energy);
}

TEST(LinearElasticity, ABlockOfSeveralBatchesIsTheSameForAnyThreadsAndKnowsItsEnergy)
{
  // 48,000 tets: more than one batch of tet matrices, added point by point in parallel.
  const int n = 20;
  const cbc3d::TetMesh mesh = cbc3d::testing::KuhnGrid(
    n, n, n, [](int, int, int) { return true; }, [](int, int, int, int) { return 1; });
  const cbc3d::Material material{ 3.0, 0.25 };
  const cbc3d::BlockMatrix serial = cbc3d::AssembleStiffness(mesh, {}, material, 1);
  const cbc3d::BlockMatrix parallel = cbc3d::AssembleStiffness(mesh, {}, material, 3);
  ASSERT_EQ(serial.Blocks(), parallel.Blocks());
  // A 3x3 block for each point and two for each edge. Kuhn's cubes have their 12 axis edges,
  // one diagonal on each face and one through the cube.
  const std::int64_t points = (n + 1) * (n + 1) * (n + 1);
  const std::int64_t edges = 3 * n * (n + 1) * (n + 1) + 3 * n * n * (n + 1) + n * n * n;
  EXPECT_EQ(serial.Blocks(), points + 2 * edges);
  EXPECT_TRUE(std::equal(serial.Values.begin(), serial.Values.end(), parallel.Values.begin()));
  EXPECT_TRUE(serial.Columns == parallel.Columns);
  const Eigen::VectorXd shift = Field(mesh, [](const Eigen::Vector3d&) { return Eigen::Vector3d(0.3, -1.0, 2.0); });
  const double largest = *std::max_element(parallel.Diagonal.begin(), parallel.Diagonal.end());
  EXPECT_LT(Times(parallel, shift).norm(), 1e-6 * largest * shift.norm()); // single precision
  const double e = 0.01;
  const Eigen::VectorXd stretch = Field(mesh, [&](const Eigen::Vector3d& x) { return Eigen::Vector3d(e * x[0], 0, 0); });
  const double lambda = material.YoungModulus * material.PoissonRatio /
    ((1 + material.PoissonRatio) * (1 - 2 * material.PoissonRatio));
  const double mu = material.YoungModulus / (2 * (1 + material.PoissonRatio));
  const double energy = 0.5 * e * e * (lambda + 2 * mu) * n * n * n;
  EXPECT_NEAR(0.5 * stretch.dot(Times(parallel, stretch)), energy, 1e-6 * energy);
  // The product sums each entry in one order: bit for bit the same on 1 and 3 threads, and
  // symmetric (u.Kv = v.Ku) to rounding.
  const Eigen::VectorXd wave = Field(mesh, [](const Eigen::Vector3d& x) {
    return Eigen::Vector3d(std::sin(x[1]), std::cos(0.5 * x[2]), x[0] * x[1] * 0.01);
  });
  const Eigen::VectorXd one = Times(serial, wave, 1), three = Times(serial, wave, 3);
  EXPECT_TRUE(std::equal(one.data(), one.data() + one.size(), three.data()));
  const Eigen::VectorXd ripple = Field(mesh, [](const Eigen::Vector3d& x) {
    return Eigen::Vector3d(std::cos(x[2]), x[0] * 0.1, std::sin(0.3 * x[1] + x[0]));
  });
  const Eigen::VectorXd rippleForce = Times(serial, ripple, 2);
  EXPECT_GT(std::abs(ripple.dot(one)), 1.0);
  EXPECT_NEAR(ripple.dot(one), wave.dot(rippleForce), 1e-12 * ripple.norm() * one.norm());
}

TEST(LinearElasticity, StopsWhenAsked)
{
  const cbc3d::BlockMatrix k =
    cbc3d::AssembleStiffness(Cube(), {}, cbc3d::Material(), 1, [](double) { return false; });
  EXPECT_EQ(k.Size(), 0);
}

TEST(ElasticStep, SpringsEverywhereTranslateTheMeshAndTheSolveMeetsItsSystem)
{
  const cbc3d::TetMesh mesh = Cube();
  const cbc3d::BlockMatrix stiffness = cbc3d::AssembleStiffness(mesh, {}, cbc3d::Material{ 3.0, 0.25 }, 1);
  cbc3d::BlockMatrix k = stiffness;
  cbc3d::ElasticStep step(std::move(k));
  ASSERT_EQ(step.Size(), 24);
  // Every point pulled the same way: a translation strains nothing, so it is the answer (but
  // for the faint anchor, a millionth of the stiffness's diagonal).
  const Eigen::Vector3d d(0.3, -1.0, 2.0);
  Eigen::VectorXd springs(24), loads(24);
  for (Eigen::Index i = 0; i < 24; ++i)
  {
    EXPECT_EQ(step.DiagonalStiffness(i), stiffness.Coefficient(i, i));
    springs[i] = step.DiagonalStiffness(i);
    loads[i] = springs[i] * d[i % 3];
  }
  ASSERT_TRUE(step.Solve(springs, loads, 2, [] { return true; }));
  for (std::size_t p = 0; p < 8; ++p)
    EXPECT_LT((step.Displacement(p) - d).norm(), 1e-3 * d.norm()) << "point " << p;
  // The bottom held, the top pulled up: the solve meets (K + P + anchor) u = P d to its tolerance.
  for (Eigen::Index i = 0; i < 24; ++i)
  {
    const Eigen::Vector3d& x = mesh.Points[i / 3];
    springs[i] = x[2] == 0.0 || x[2] == 2.0 ? 10.0 * stiffness.Coefficient(i, i) : 0.0;
    loads[i] = x[2] == 2.0 && i % 3 == 2 ? springs[i] * 0.1 : 0.0;
  }
  ASSERT_TRUE(step.Solve(springs, loads, 1, [] { return true; }));
  Eigen::VectorXd u(24);
  for (std::size_t p = 0; p < 8; ++p)
    u.segment<3>(3 * p) = step.Displacement(p);
  const Eigen::VectorXd anchored = springs + 1e-6 * Dense(stiffness).diagonal();
  const Eigen::VectorXd residual = Times(stiffness, u) + anchored.cwiseProduct(u) - loads;
  EXPECT_LT(residual.norm(), 1e-4 * loads.norm());
  EXPECT_GT(u[3 * 7 + 2], 0.0); // the top corner rose
  // A stop at the first poll leaves the last step as it was.
  EXPECT_FALSE(step.Solve(springs, 2.0 * loads, 1, [] { return false; }));
  EXPECT_EQ(step.Displacement(7), Eigen::Vector3d(u.segment<3>(21)));
}
