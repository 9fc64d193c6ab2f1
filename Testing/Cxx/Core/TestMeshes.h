// Small tet meshes with known topology, shared by the core unit tests.
#ifndef cbc3d_TestMeshes_h
#define cbc3d_TestMeshes_h

#include "cbc3d/base/TetGeometry.h"
#include "cbc3d/base/TetMesh.h"

#include <array>
#include <utility>

namespace cbc3d
{
namespace testing
{
// Appends a tet over new points, positively oriented.
inline void AddTet(TetMesh& mesh, Tet tet, std::int32_t label = 1)
{
  const auto& p = mesh.Points;
  if (SignedVolume(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]) < 0)
    std::swap(tet[1], tet[2]);
  mesh.Tets.push_back(tet);
  mesh.Labels.push_back(label);
}

// The unit tet 0..3, plus the points of a second tet as the tests below need them.
inline TetMesh OneTet()
{
  TetMesh mesh;
  mesh.Points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  AddTet(mesh, { 0, 1, 2, 3 });
  return mesh;
}

// The cubes (x, y, z) of a grid for which `solid` holds, each split into the six Kuhn tets along
// its diagonal from (x, y, z); one diagonal direction everywhere makes neighbouring cubes
// conform. `labelOf(x, y, z, tet)` labels tet 0..5 of a cube, in cyclic order around the
// diagonal (consecutive ones share a face).
template <typename Solid, typename LabelOf>
TetMesh KuhnGrid(int nx, int ny, int nz, Solid solid, LabelOf labelOf)
{
  TetMesh mesh;
  auto id = [&](int x, int y, int z) { return PointId(x + (nx + 1) * (y + (ny + 1) * z)); };
  for (int z = 0; z <= nz; ++z)
    for (int y = 0; y <= ny; ++y)
      for (int x = 0; x <= nx; ++x)
        mesh.Points.emplace_back(x, y, z);
  // Axis orders around the diagonal: x y z, y x z, y z x, z y x, z x y, x z y.
  const int orders[6][3] = { { 0, 1, 2 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 1, 0 }, { 2, 0, 1 }, { 0, 2, 1 } };
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
      {
        if (!solid(x, y, z))
          continue;
        for (int t = 0; t < 6; ++t)
        {
          std::array<int, 3> at = { x, y, z };
          Tet tet;
          tet[0] = id(at[0], at[1], at[2]);
          for (int step = 0; step < 3; ++step)
          {
            ++at[orders[t][step]];
            tet[step + 1] = id(at[0], at[1], at[2]);
          }
          AddTet(mesh, tet, labelOf(x, y, z, t));
        }
      }
  return mesh;
}

} // namespace testing
} // namespace cbc3d

#endif
