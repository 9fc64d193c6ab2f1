#include "cbc3d/base/TetGeometry.h"
#include "cbc3d/base/TetMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

using cbc3d::Vec3;

namespace
{
double Degrees(double radians)
{
  return radians * cbc3d::RadiansToDegrees;
}
} // namespace

TEST(TetGeometry, RegularTetHasSixAnglesOfArccosOneThird)
{
  const Vec3 p0(1, 1, 1), p1(1, -1, -1), p2(-1, 1, -1), p3(-1, -1, 1);
  const double expected = Degrees(std::acos(1.0 / 3.0)); // 70.5288 degrees
  EXPECT_NEAR(expected, 70.5288, 1e-4);
  for (const double angle : cbc3d::DihedralAngles(p0, p1, p2, p3))
  {
    EXPECT_NEAR(Degrees(angle), expected, 1e-9);
  }
  // Edge length 2*sqrt(2): volume a^3 / (6 sqrt 2) = 8/3.
  EXPECT_NEAR(std::abs(cbc3d::SignedVolume(p0, p1, p2, p3)), 8.0 / 3.0, 1e-12);
}

TEST(TetGeometry, BCCTetHasFourSixtyAndTwoNinetyDegreeAngles)
{
  // Two adjacent cube centres and one edge of the face they share.
  const Vec3 c0(0.5, 0.5, 0.5), c1(1.5, 0.5, 0.5), q0(1, 0, 0), q1(1, 1, 0);
  auto angles = cbc3d::DihedralAngles(c0, c1, q0, q1);
  std::sort(angles.begin(), angles.end());
  for (int i = 0; i < 4; ++i)
  {
    EXPECT_NEAR(Degrees(angles[i]), 60.0, 1e-9);
  }
  EXPECT_NEAR(Degrees(angles[4]), 90.0, 1e-9);
  EXPECT_NEAR(Degrees(angles[5]), 90.0, 1e-9);
}

TEST(TetGeometry, UnitRightTetIsPositiveInVTKOrder)
{
  const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  EXPECT_NEAR(cbc3d::SignedVolume(o, x, y, z), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(cbc3d::SignedVolume(o, y, x, z), -1.0 / 6.0, 1e-15);
  // Right angles at the three edges through the origin, arccos(1/sqrt 3) at the others.
  const auto angles = cbc3d::DihedralAngles(o, x, y, z); // edges 01 12 20 03 13 23
  EXPECT_NEAR(Degrees(angles[0]), 90.0, 1e-9);
  EXPECT_NEAR(Degrees(angles[2]), 90.0, 1e-9);
  EXPECT_NEAR(Degrees(angles[3]), 90.0, 1e-9);
  const double oblique = Degrees(std::acos(1.0 / std::sqrt(3.0)));
  EXPECT_NEAR(Degrees(angles[1]), oblique, 1e-9);
  EXPECT_NEAR(Degrees(angles[4]), oblique, 1e-9);
  EXPECT_NEAR(Degrees(angles[5]), oblique, 1e-9);
}

TEST(TetGeometry, SliverAngleAtEdgeZeroTwoIsThreeDegrees)
{
  // The faces (0,2,1) and (0,2,3) meet at 3 degrees along edge 0-2 (the x axis).
  const double a = 3.0 / cbc3d::RadiansToDegrees;
  const Vec3 p0(0, 0, 0), p1(0.5, 1, 0), p2(1, 0, 0), p3(0.5, std::cos(a), std::sin(a));
  const auto angles = cbc3d::DihedralAngles(p0, p1, p2, p3);
  EXPECT_NEAR(Degrees(angles[2]), 3.0, 1e-9); // edge {2,0}
  EXPECT_NEAR(Degrees(*std::min_element(angles.begin(), angles.end())), 3.0, 1e-9);
}

TEST(TetGeometry, AnglesWithinAgreesWithTheAngles)
{
  // A regular tet: every dihedral angle is arccos(1/3) = 70.53 degrees.
  const double s = std::sqrt(8.0 / 9.0), r = std::sqrt(2.0 / 9.0), h = std::sqrt(2.0 / 3.0);
  const Eigen::Vector3d a(s, 0, -1.0 / 3), b(-r, h, -1.0 / 3), c(-r, -h, -1.0 / 3), d(0, 0, 1);
  const double regular = std::acos(1.0 / 3.0);
  EXPECT_TRUE(cbc3d::DihedralAnglesWithin(a, b, c, d, regular - 1e-6));
  EXPECT_FALSE(cbc3d::DihedralAnglesWithin(a, b, c, d, regular + 1e-6));
  EXPECT_FALSE(cbc3d::DihedralAnglesWithin(a, b, c, a, 0.1)); // degenerate
  EXPECT_NEAR(cbc3d::LargestDihedralCosine(a, b, c, d), 1.0 / 3.0, 1e-12);
  EXPECT_EQ(cbc3d::LargestDihedralCosine(a, b, c, a), 1.0);
  // The sliver's 3-degree angle sets the largest |cos|.
  const double sliver = 3.0 / cbc3d::RadiansToDegrees;
  EXPECT_NEAR(cbc3d::LargestDihedralCosine(Vec3(0, 0, 0), Vec3(0.5, 1, 0), Vec3(1, 0, 0),
                Vec3(0.5, std::cos(sliver), std::sin(sliver))),
    std::cos(sliver), 1e-12);
  // Random tets, each bound: the same verdict as the smallest and largest angle.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int n = 0; n < 2000; ++n)
  {
    std::array<Eigen::Vector3d, 4> p;
    for (auto& q : p)
      q = Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
    const auto angles = cbc3d::DihedralAngles(p[0], p[1], p[2], p[3]);
    const double smallest = *std::min_element(angles.begin(), angles.end());
    const double largest = *std::max_element(angles.begin(), angles.end());
    for (const double bound : { 0.1, 0.35, 0.6 })
    {
      const bool within = smallest >= bound && largest <= M_PI - bound;
      if (std::abs(smallest - bound) > 1e-9 && std::abs(M_PI - largest - bound) > 1e-9)
        EXPECT_EQ(cbc3d::DihedralAnglesWithin(p[0], p[1], p[2], p[3], bound), within);
    }
  }
}

// The share of a tet beyond a plane: a corner cut at half its edges is an eighth, a plane
// through the midpoints of four edges halves a tet, the two sides sum to one, and a fine
// quadrature over the tet agrees.
TEST(TetGeometry, ShareAboveAPlaneHasItsKnownValues)
{
  EXPECT_NEAR(cbc3d::ShareAbove({ 1, -1, -1, -1 }), 0.125, 1e-15);
  EXPECT_NEAR(cbc3d::ShareAbove({ -1, 1, 1, 1 }), 0.875, 1e-15);
  EXPECT_NEAR(cbc3d::ShareAbove({ 1, 1, -1, -1 }), 0.5, 1e-15);
  EXPECT_EQ(cbc3d::ShareAbove({ -1, -2, -3, 0 }), 0.0);
  EXPECT_EQ(cbc3d::ShareAbove({ 1, 2, 3, 4 }), 1.0);
  for (const std::array<double, 4>& d : { std::array<double, 4>{ 1, 2, -1, -3 }, std::array<double, 4>{ 0.5, -2, 3, -1 },
         std::array<double, 4>{ 4, -1, -0.5, -2 }, std::array<double, 4>{ -0.3, 2, 1, 0.7 } })
  {
    const std::array<double, 4> flipped = { -d[0], -d[1], -d[2], -d[3] };
    EXPECT_NEAR(cbc3d::ShareAbove(d) + cbc3d::ShareAbove(flipped), 1.0, 1e-12);
    // Midpoint quadrature on n^3 sub-cells of the barycentric simplex.
    const int n = 120;
    double above = 0.0, all = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j)
        for (int k = 0; i + j + k < n; ++k)
        {
          const double a = (i + 0.25) / n, b = (j + 0.25) / n, c = (k + 0.25) / n, w = 1.0 - a - b - c;
          above += (w * d[0] + a * d[1] + b * d[2] + c * d[3]) > 0.0;
          all += 1.0;
        }
    EXPECT_NEAR(cbc3d::ShareAbove(d), above / all, 0.01) << d[0] << " " << d[1] << " " << d[2] << " " << d[3];
  }
}

TEST(TetMesh, PointIdsHoldUpToTwoToTheThirtyOneMinusOnePoints)
{
  EXPECT_EQ(cbc3d::MaxPoints, std::size_t(2147483647));
  EXPECT_NO_THROW(cbc3d::CheckPointCount(cbc3d::MaxPoints));
  EXPECT_THROW(cbc3d::CheckPointCount(cbc3d::MaxPoints + 1), std::length_error);
}
