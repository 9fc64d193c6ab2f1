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

  const std::vector<Eigen::Vector3d> none;
  EXPECT_EQ(cbc3d::PointGrid(none, 1.0).NearestAny(Eigen::Vector3d::Zero()), -1);
}
