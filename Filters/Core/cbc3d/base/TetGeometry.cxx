#include "cbc3d/base/TetGeometry.h"

#include "cbc3d/base/TetTopology.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace cbc3d
{
double SignedVolume(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3)
{
  return (p1 - p0).cross(p2 - p0).dot(p3 - p0) / 6.0;
}

std::array<double, 6> DihedralAngles(const Vec3& p0, const Vec3& p1, const Vec3& p2,
  const Vec3& p3)
{
  const std::array<const Vec3*, 4> p = { &p0, &p1, &p2, &p3 };
  std::array<double, 6> angles{};
  for (int e = 0; e < 6; ++e)
  {
    const int a = TetEdges[e][0];
    const int b = TetEdges[e][1];
    // The two vertices off the edge span the two faces that meet at it.
    const int c = (a != 0 && b != 0) ? 0 : ((a != 1 && b != 1) ? 1 : 2);
    const int d = 6 - a - b - c;
    const Vec3 axis = (*p[b] - *p[a]).normalized();
    Vec3 u = *p[c] - *p[a];
    Vec3 v = *p[d] - *p[a];
    u -= u.dot(axis) * axis;
    v -= v.dot(axis) * axis;
    // atan2 stays accurate near 0 and 180 degrees, where acos of a dot product does not.
    angles[e] = std::atan2(u.cross(v).norm(), u.dot(v));
  }
  return angles;
}

double LargestDihedralCosine(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3)
{
  // The dihedral angle at the edge shared by two faces is the angle between their normals or
  // its supplement, so |cos| of the normals' angle measures both at once.
  const std::array<Vec3, 4> normals = { (p2 - p1).cross(p3 - p1), (p3 - p0).cross(p2 - p0),
    (p1 - p0).cross(p3 - p0), (p2 - p0).cross(p1 - p0) };
  std::array<double, 4> lengths;
  for (int f = 0; f < 4; ++f)
  {
    lengths[f] = normals[f].norm();
    if (!(lengths[f] > 0.0))
    {
      return 1.0;
    }
  }
  double largest = 0.0;
  for (int f = 0; f < 4; ++f)
  {
    for (int g = f + 1; g < 4; ++g)
    {
      largest = std::max(largest, std::abs(normals[f].dot(normals[g])) / (lengths[f] * lengths[g]));
    }
  }
  return largest;
}

bool DihedralAnglesWithin(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3,
  double minimum)
{
  return LargestDihedralCosine(p0, p1, p2, p3) <= std::cos(minimum);
}

double LongestEdge(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3)
{
  return std::sqrt(std::max({ (p1 - p0).squaredNorm(), (p2 - p0).squaredNorm(), (p3 - p0).squaredNorm(),
    (p2 - p1).squaredNorm(), (p3 - p1).squaredNorm(), (p3 - p2).squaredNorm() }));
}

double ShareAbove(const std::array<double, 4>& values)
{
  std::array<int, 4> above{}, below{};
  int aboveCount = 0, belowCount = 0;
  for (int c = 0; c < 4; ++c)
  {
    if (values[c] > 0.0)
      above[aboveCount++] = c;
    else
      below[belowCount++] = c;
  }
  if (aboveCount == 0 || belowCount == 0)
    return aboveCount == 0 ? 0.0 : 1.0;
  // One corner alone on its side: a corner tet, scaled along its three edges.
  auto corner = [&](int alone, const std::array<int, 4>& others, int count) {
    double share = 1.0;
    for (int o = 0; o < count; ++o)
      share *= values[alone] / (values[alone] - values[others[o]]);
    return share;
  };
  if (aboveCount == 1)
    return corner(above[0], below, 3);
  if (belowCount == 1)
    return 1.0 - corner(below[0], above, 3);
  // Two and two: a prism between the two corners above and the plane, in the unit tet (the
  // share is the same in any tet), as three tets.
  const std::array<Vec3, 4> unit = { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1) };
  auto cut = [&](int i, int j) -> Vec3 { return unit[i] + values[i] / (values[i] - values[j]) * (unit[j] - unit[i]); };
  const Vec3 A = unit[above[0]], B = unit[above[1]];
  const Vec3 P = cut(above[0], below[0]), Q = cut(above[0], below[1]), R = cut(above[1], below[0]),
             S = cut(above[1], below[1]);
  const double volume = std::abs(SignedVolume(A, P, Q, B)) + std::abs(SignedVolume(P, Q, B, R)) +
    std::abs(SignedVolume(Q, B, R, S));
  return 6.0 * volume; // the unit tet's volume is 1/6
}
} // namespace cbc3d
