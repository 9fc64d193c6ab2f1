// PointGrid against brute force: the nearest point within a radius, ties, and far queries.
#include "cbc3d/base/PointGrid.h"

#include <gtest/gtest.h>

#include <random>

namespace
{
int BruteNearest(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& x, double radius)
{
  int best = -1;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const double d = (points[i] - x).norm();
    if (d <= radius && (best < 0 || d < (points[best] - x).norm()))
    {
      best = static_cast<int>(i);
    }
  }
  return best;
}

// `count` points uniform in the cube [-20, 20]^3, drawn from `random`.
std::vector<Eigen::Vector3d> RandomPoints(std::size_t count, std::mt19937& random)
{
  std::uniform_real_distribution<double> coordinate(-20.0, 20.0);
  std::vector<Eigen::Vector3d> points(count);
  for (auto& p : points)
    p = Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
  return points;
}
} // namespace

TEST(PointGrid, MatchesBruteForceOnRandomPoints)
{
  std::mt19937 random(7);
  const std::vector<Eigen::Vector3d> points = RandomPoints(500, random);
  const cbc3d::PointGrid grid(points, 1.5);
  for (const Eigen::Vector3d& x : RandomPoints(300, random))
  {
    EXPECT_EQ(grid.Nearest(x, 3.0), BruteNearest(points, x, 3.0));
    EXPECT_EQ(grid.NearestAny(x), BruteNearest(points, x, 1e9));
  }
}

TEST(PointGrid, BuiltOnThreadsMatchesBruteForce)
{
  // Bucketed on 4 threads: each answer the nearest point's, ties to the lower index.
  std::mt19937 random(11);
  std::vector<Eigen::Vector3d> points = RandomPoints(20000, random);
  points[17] = points[9]; // a tie
  const cbc3d::PointGrid grid(points, 1.0, 4);
  std::vector<Eigen::Vector3d> queries = RandomPoints(200, random);
  queries.push_back(points[17]);
  const std::vector<int> nearest = grid.NearestAnyOfAll(queries, 1);
  for (std::size_t q = 0; q < queries.size(); ++q)
    EXPECT_EQ(nearest[q], BruteNearest(points, queries[q], 1e9)) << "query " << q;
  EXPECT_EQ(nearest.back(), 9);
}

TEST(PointGrid, RadiusTiesAndFilters)
{
  const std::vector<Eigen::Vector3d> points = { { 2, 0, 0 }, { -2, 0, 0 }, { 0, 5, 0 } };
  const cbc3d::PointGrid grid(points, 1.0);
  EXPECT_EQ(grid.Nearest(Eigen::Vector3d::Zero(), 1.9), -1); // nothing within the radius
  EXPECT_EQ(grid.Nearest(Eigen::Vector3d::Zero(), 2.0), 0);  // a tie goes to the lower index
  EXPECT_EQ(grid.Nearest(Eigen::Vector3d::Zero(), 10.0, [](int i) { return i != 0; }), 1);
  EXPECT_EQ(grid.NearestAny(Eigen::Vector3d(0, 100, 0)), 2); // far outside every cell searched first

  EXPECT_EQ(grid.Nearest(Eigen::Vector3d::Zero(), -1.0), -1);      // a negative radius finds nothing

  const std::vector<Eigen::Vector3d> none;
  EXPECT_EQ(cbc3d::PointGrid(none, 1.0).NearestAny(Eigen::Vector3d::Zero()), -1);
}

// Integer lattice points give many exact ties; queries inside, on faces and far outside the
// grid, with a filter, at cell sizes smaller and larger than the spacing.
TEST(PointGrid, MatchesBruteForceWithTiesFiltersAndFarQueries)
{
  std::vector<Eigen::Vector3d> points;
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 7; ++x)
      {
        if ((x * 7 + y * 3 + z) % 4 != 0) // a sparse, uneven subset
        {
          points.emplace_back(2.0 * x, 2.0 * y, 2.0 * z);
        }
      }
  auto brute = [&points](const Eigen::Vector3d& x, double radius, auto accept) {
    int best = -1;
    double bestDistance = radius * radius;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      const double d = (points[i] - x).squaredNorm();
      if (accept(int(i)) && (d < bestDistance || (best < 0 && d == bestDistance)))
      {
        best = static_cast<int>(i);
        bestDistance = d;
      }
    }
    return best;
  };
  auto everyThird = [](int i) { return i % 3 == 0; };
  auto all = [](int) { return true; };
  std::mt19937 random(11);
  std::uniform_int_distribution<int> half(-30, 50); // half-units: on points, faces and outside
  for (const double cell : { 0.7, 2.0, 5.0 })
  {
    const cbc3d::PointGrid grid(points, cell);
    for (int q = 0; q < 400; ++q)
    {
      const Eigen::Vector3d x(0.5 * half(random), 0.5 * half(random), 0.5 * half(random));
      for (const double radius : { 0.0, 1.0, 2.0, 4.5, 1e9 })
      {
        EXPECT_EQ(grid.Nearest(x, radius), brute(x, radius, all)) << cell << " " << radius;
        EXPECT_EQ(grid.Nearest(x, radius, everyThird), brute(x, radius, everyThird)) << cell;
      }
      EXPECT_EQ(grid.NearestAny(x), brute(x, 1e300, all));
    }
    EXPECT_EQ(grid.NearestAny(Eigen::Vector3d(1e12, -1e12, 3.0)), brute(Eigen::Vector3d(1e12, -1e12, 3.0), 1e300, all));
  }
}

namespace
{
// The nearest by squared distance, the lower index on a tie: NearestAny's rule.
int BruteNearestAny(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& x)
{
  int best = -1;
  double bestDistance = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const double d = (points[i] - x).squaredNorm();
    if (best < 0 || d < bestDistance)
    {
      best = static_cast<int>(i);
      bestDistance = d;
    }
  }
  return best;
}

// NearestAnyOfAll against brute force and against NearestAny, on 1 and 3 threads.
void ExpectNearestOfAll(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& queries,
  double cell)
{
  const cbc3d::PointGrid grid(points, cell);
  for (const int threads : { 1, 3 })
  {
    const std::vector<int> nearest = grid.NearestAnyOfAll(queries, threads);
    ASSERT_EQ(nearest.size(), queries.size());
    for (std::size_t q = 0; q < queries.size(); ++q)
    {
      ASSERT_EQ(nearest[q], BruteNearestAny(points, queries[q])) << "query " << q << " threads " << threads;
      ASSERT_EQ(nearest[q], grid.NearestAny(queries[q])) << "query " << q;
    }
  }
}

// `count` random points on the sphere of `radius` about the origin.
std::vector<Eigen::Vector3d> SpherePoints(std::size_t count, double radius, unsigned seed)
{
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Vector3d> points(count);
  for (auto& p : points)
    p = radius * Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized();
  return points;
}

// The points of the lattice of `step` within `extent` of the origin per axis whose distance
// from the origin lies in (inner, outer): voxel centres around a sphere.
std::vector<Eigen::Vector3d> ShellLattice(double extent, double step, double inner, double outer)
{
  std::vector<Eigen::Vector3d> points;
  for (double x = -extent; x <= extent; x += step)
    for (double y = -extent; y <= extent; y += step)
      for (double z = -extent; z <= extent; z += step)
      {
        const double r = std::sqrt(x * x + y * y + z * z);
        if (r > inner && r < outer)
          points.emplace_back(x, y, z);
      }
  return points;
}
} // namespace

TEST(PointGrid, NearestOfAllDenseQueriesAgainstSparsePoints)
{
  // Vertices on a sphere, voxel centres on a finer lattice in a shell around it and some far
  // off: many queries per cell, answered cell by cell.
  const std::vector<Eigen::Vector3d> points = SpherePoints(400, 10.0, 5);
  std::vector<Eigen::Vector3d> queries = ShellLattice(12.0, 0.5, 9.0, 11.0);
  queries.emplace_back(100.0, -3.0, 40.0);
  queries.emplace_back(-250.0, 0.0, 0.0);
  ASSERT_GT(queries.size(), 4000u);
  ExpectNearestOfAll(points, queries, 2.5);
}

TEST(PointGrid, NearestOfAllTiesOnALattice)
{
  // Points on an integer lattice, queries on the half-integer one and on the points: many
  // queries equally far from 2, 4 or 8 points; the lower index must win each time.
  std::vector<Eigen::Vector3d> points, queries;
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 6; ++y)
      for (int x = 5; x >= 0; --x) // indices not in coordinate order
        points.emplace_back(2.0 * x, 2.0 * y, 2.0 * z);
  for (int z = -2; z < 24; ++z)
    for (int y = -2; y < 24; ++y)
      for (int x = -2; x < 24; ++x)
        queries.emplace_back(0.5 * x, 0.5 * y, 0.5 * z);
  ExpectNearestOfAll(points, queries, 2.0);
  ExpectNearestOfAll(points, queries, 0.7);
}

TEST(PointGrid, NearestOfAllFewQueriesAndEmptyGrid)
{
  std::mt19937 random(9);
  std::uniform_real_distribution<double> coordinate(-20.0, 20.0);
  std::vector<Eigen::Vector3d> points(300), queries(50);
  for (auto& p : points)
    p = Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
  for (auto& q : queries)
    q = Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
  ExpectNearestOfAll(points, queries, 1.0); // one query per cell or so: searched one by one
  const std::vector<Eigen::Vector3d> none;
  const cbc3d::PointGrid empty(none, 1.0);
  EXPECT_EQ(empty.NearestAnyOfAll(queries, 2), std::vector<int>(queries.size(), -1));
  EXPECT_TRUE(cbc3d::PointGrid(points, 1.0).NearestAnyOfAll(none, 2).empty());
}

TEST(PointGrid, NearestOfAllWithARadiusAndAFilter)
{
  // Sources on a sphere, targets dense around it: each target takes the nearest source within
  // the radius that its filter accepts (here: a source of the same parity as the target, and
  // none for every seventh target); cell by cell and one by one agree, ties included.
  std::vector<Eigen::Vector3d> points = SpherePoints(300, 8.0, 13);
  points.push_back(points[10]); // a tie: the same position twice
  std::vector<Eigen::Vector3d> queries = ShellLattice(9.5, 0.5, 7.0, 9.0);
  queries.push_back(points[10]);
  auto accept = [](std::int64_t q, int index) { return q % 7 != 0 && (q + index) % 2 == 0; };
  for (const double cell : { 1.0, 2.5 })
  {
    const cbc3d::PointGrid grid(points, cell);
    for (const double radius : { 0.75, 2.0 })
    {
      const std::vector<int> nearest = grid.NearestOfAll(queries, radius, accept, 3);
      ASSERT_EQ(nearest.size(), queries.size());
      int found = 0;
      for (std::size_t q = 0; q < queries.size(); ++q)
      {
        const std::int64_t query = static_cast<std::int64_t>(q);
        ASSERT_EQ(nearest[q], grid.Nearest(queries[q], radius, [&](int index) { return accept(query, index); }))
          << "query " << q << " cell " << cell << " radius " << radius;
        found += nearest[q] >= 0;
      }
      EXPECT_GT(found, 100); // the radius and filter leave answers to compare
    }
  }
}

TEST(PointGrid, NearestOfAllCarriesAnErrorOutOfItsThreads)
{
  // An exception in a thread of a parallel region would end the process (std::terminate); one
  // thrown while searching, shared lists or one by one, reaches the caller instead.
  const std::vector<Eigen::Vector3d> points = SpherePoints(300, 8.0, 13);
  const std::vector<Eigen::Vector3d> dense = ShellLattice(9.5, 0.5, 7.0, 9.0);
  const std::vector<Eigen::Vector3d> sparse(dense.begin(), dense.begin() + 20);
  const cbc3d::PointGrid grid(points, 1.0);
  auto failing = [](std::int64_t q, int) -> bool {
    if (q % 5 == 3)
      throw std::bad_alloc();
    return true;
  };
  for (const auto* queries : { &dense, &sparse })
  {
    EXPECT_THROW(grid.NearestOfAll(*queries, 2.0, failing, 4), std::bad_alloc);
    EXPECT_THROW(grid.NearestOfAll(*queries, 2.0, failing, 1), std::bad_alloc);
  }
}
