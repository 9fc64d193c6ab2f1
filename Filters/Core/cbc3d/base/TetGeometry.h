#ifndef cbc3d_TetGeometry_h
#define cbc3d_TetGeometry_h

#include <Eigen/Core>

#include <array>

namespace cbc3d
{
using Vec3 = Eigen::Vector3d;

/// Signed volume; positive for a tet oriented as VTK_TETRA expects.
double SignedVolume(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3);

/// The six interior dihedral angles in radians, at the edges in TetEdges order.
std::array<double, 6> DihedralAngles(const Vec3& p0, const Vec3& p1, const Vec3& p2,
  const Vec3& p3);

/// The largest |cos| of the six dihedral angles: the cosine of the angle margin (the smallest
/// of each angle and 180 degrees minus it), without trigonometry. 1 for a tet with a
/// degenerate face.
double LargestDihedralCosine(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3);

/// Whether every dihedral angle lies within [minimum, pi - minimum] (radians): the same test as
/// DihedralAngles against the bound, by the cosines between face normals, which costs no
/// trigonometry. A tet with a degenerate face fails.
bool DihedralAnglesWithin(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3,
  double minimum);

/// The centroid: the mean of the four corners.
inline Vec3 Centroid(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3)
{
  return 0.25 * (p0 + p1 + p2 + p3);
}

/// The length of the longest of the six edges.
double LongestEdge(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3);

/// The share of a tet's volume where a linear function is positive, from its values at the
/// four corners (it depends on nothing else): the part of a tet beyond a plane, with the
/// corners' signed distances to it.
double ShareAbove(const std::array<double, 4>& values);

constexpr double RadiansToDegrees = 57.295779513082320876798154814105;
} // namespace cbc3d

#endif
