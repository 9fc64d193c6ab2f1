#include "cbc3d/lattice/RedGreenTables.h"

#include "cbc3d/base/TetTopology.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <map>

namespace cbc3d
{
namespace
{
int EdgeIndex(int a, int b)
{
  for (int e = 0; e < 6; ++e)
  {
    if ((TetEdges[e][0] == a && TetEdges[e][1] == b) || (TetEdges[e][0] == b && TetEdges[e][1] == a))
    {
      return e;
    }
  }
  return -1;
}

// The local number of the midpoint of edge (a, b).
std::uint8_t Mid(int a, int b)
{
  return static_cast<std::uint8_t>(4 + EdgeIndex(a, b));
}

struct Template
{
  std::uint8_t Mask;
  std::vector<LocalTet> Children;
};

// The three green templates, by substituting midpoints for corners (which keeps orientation).
std::vector<Template> GreenTemplates()
{
  const std::uint8_t m01 = Mid(0, 1), m12 = Mid(1, 2), m20 = Mid(2, 0), m23 = Mid(2, 3);
  return {
    { 1u << 0, { { m01, 1, 2, 3 }, { 0, m01, 2, 3 } } },
    { (1u << 0) | (1u << 5),
      { { m01, 1, m23, 3 }, { m01, 1, 2, m23 }, { 0, m01, m23, 3 }, { 0, m01, 2, m23 } } },
    { (1u << 0) | (1u << 1) | (1u << 2),
      { { 0, m01, m20, 3 }, { m01, 1, m12, 3 }, { m20, m12, 2, 3 }, { m01, m12, m20, 3 } } },
  };
}

// The 12 even permutations of the corners: rotations of the tet.
std::vector<std::array<int, 4>> Rotations()
{
  std::vector<std::array<int, 4>> result;
  std::array<int, 4> p = { 0, 1, 2, 3 };
  do
  {
    int inversions = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        inversions += p[i] > p[j];
    if (inversions % 2 == 0)
    {
      result.push_back(p);
    }
  } while (std::next_permutation(p.begin(), p.end()));
  return result;
}

std::uint8_t MapPoint(std::uint8_t local, const std::array<int, 4>& rotation)
{
  if (local < 4)
  {
    return static_cast<std::uint8_t>(rotation[local]);
  }
  const auto& edge = TetEdges[local - 4];
  return static_cast<std::uint8_t>(4 + EdgeIndex(rotation[edge[0]], rotation[edge[1]]));
}

std::map<std::uint8_t, std::vector<LocalTet>> BuildGreenTable()
{
  std::map<std::uint8_t, std::vector<LocalTet>> table;
  table[0] = { LocalTet{ 0, 1, 2, 3 } };
  for (const Template& green : GreenTemplates())
  {
    for (const auto& rotation : Rotations())
    {
      std::uint8_t mask = 0;
      for (int e = 0; e < 6; ++e)
      {
        if (green.Mask & (1u << e))
        {
          mask |= static_cast<std::uint8_t>(1u << EdgeIndex(rotation[TetEdges[e][0]], rotation[TetEdges[e][1]]));
        }
      }
      std::vector<LocalTet> children;
      for (const LocalTet& child : green.Children)
      {
        children.push_back({ MapPoint(child[0], rotation), MapPoint(child[1], rotation),
          MapPoint(child[2], rotation), MapPoint(child[3], rotation) });
      }
      table.emplace(mask, children); // rotations that give the same mask give the same split
    }
  }
  return table;
}

std::array<std::array<LocalTet, 8>, 3> BuildRedTable()
{
  // Positions of the local points on a reference tet, to orient the octahedron's children.
  std::array<Eigen::Vector3d, 10> p = { Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
    Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1) };
  for (int e = 0; e < 6; ++e)
  {
    p[4 + e] = 0.5 * (p[TetEdges[e][0]] + p[TetEdges[e][1]]);
  }
  std::array<std::array<LocalTet, 8>, 3> table;
  for (int d = 0; d < 3; ++d)
  {
    auto& children = table[d];
    // The corner tets: each corner with the midpoints of its three edges.
    children[0] = { 0, Mid(0, 1), Mid(2, 0), Mid(0, 3) };
    children[1] = { Mid(0, 1), 1, Mid(1, 2), Mid(1, 3) };
    children[2] = { Mid(2, 0), Mid(1, 2), 2, Mid(2, 3) };
    children[3] = { Mid(0, 3), Mid(1, 3), Mid(2, 3), 3 };
    // The octahedron around the diagonal from edge (i,j)'s midpoint to edge (k,l)'s: its other
    // four vertices form the cycle ik, jk, jl, il.
    const auto& first = TetEdges[d];
    const auto& second = TetEdges[OppositeEdge[d]];
    const int i = first[0], j = first[1], k = second[0], l = second[1];
    const std::uint8_t a = static_cast<std::uint8_t>(4 + d), b = static_cast<std::uint8_t>(4 + OppositeEdge[d]);
    const std::uint8_t ring[4] = { Mid(i, k), Mid(j, k), Mid(j, l), Mid(i, l) };
    for (int r = 0; r < 4; ++r)
    {
      LocalTet child = { a, b, ring[r], ring[(r + 1) % 4] };
      const double volume = (p[child[1]] - p[child[0]]).cross(p[child[2]] - p[child[0]]).dot(p[child[3]] - p[child[0]]);
      if (volume < 0)
      {
        std::swap(child[2], child[3]);
      }
      children[4 + r] = child;
    }
  }
  return table;
}
} // namespace

const std::vector<LocalTet>* GreenClosure(std::uint8_t edgeMask)
{
  static const std::map<std::uint8_t, std::vector<LocalTet>> table = BuildGreenTable();
  const auto found = table.find(edgeMask);
  return found == table.end() ? nullptr : &found->second;
}

const std::array<LocalTet, 8>& RedChildren(int diagonal)
{
  static const std::array<std::array<LocalTet, 8>, 3> table = BuildRedTable();
  return table.at(diagonal);
}
} // namespace cbc3d
