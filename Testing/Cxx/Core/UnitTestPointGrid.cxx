// PointGrid against brute force: the nearest point within a radius, ties, and far queries.
#include "cbc3d/PointGrid.h"

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
} // namespace

TEST(PointGrid, MatchesBruteForceOnRandomPoints)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-20.0, 20.0);
  std::vector<Eigen::Vector3d> points(500);
  for (auto& p : points)
  {
    p = Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
  }
  const cbc3d::PointGrid grid(points, 1.5);
  for (int q = 0; q < 300; ++q)
  {
    const Eigen::Vector3d x(coordinate(random), coordinate(random), coordinate(random));
    EXPECT_EQ(grid.Nearest(x, 3.0), BruteNearest(points, x, 3.0));
    EXPECT_EQ(grid.NearestAny(x), BruteNearest(points, x, 1e9));
  }
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
