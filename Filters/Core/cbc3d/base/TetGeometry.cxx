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
} // namespace cbc3d
