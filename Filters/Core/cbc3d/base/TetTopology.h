#ifndef cbc3d_TetTopology_h
#define cbc3d_TetTopology_h

#include <array>

namespace cbc3d
{
/// Edge and face tables in VTK_TETRA order (vtkTetra.cxx), so a core tet is a VTK tet with no
/// reordering. A tet is positively oriented when (p1-p0) x (p2-p0) . (p3-p0) > 0, that is,
/// (0,1,2) is counter-clockwise seen from 3.
constexpr std::array<std::array<int, 2>, 6> TetEdges = { { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 },
  { 1, 3 }, { 2, 3 } } };
constexpr std::array<std::array<int, 3>, 4> TetFaces = { { { 0, 1, 3 }, { 1, 2, 3 }, { 2, 0, 3 },
  { 0, 2, 1 } } };
/// The edge opposite each edge (sharing no vertex with it): 01-23, 12-03, 20-13.
constexpr std::array<int, 6> OppositeEdge = { 5, 3, 4, 1, 2, 0 };
} // namespace cbc3d

#endif
