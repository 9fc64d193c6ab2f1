#include "cbc3d/MeshFaces.h"

#include "cbc3d/TetTopology.h"

#include <algorithm>
#include <tuple>

namespace cbc3d
{
std::vector<MeshFace> FindMeshFaces(const std::vector<Tet>& tets, std::size_t pointCount)
{
  struct Entry
  {
    PointId B, C;
    std::int64_t Tet;
    bool operator<(const Entry& o) const { return std::tie(B, C, Tet) < std::tie(o.B, o.C, o.Tet); }
  };
  auto sortedFace = [&tets](std::size_t t, int f) {
    std::array<PointId, 3> ids = { tets[t][TetFaces[f][0]], tets[t][TetFaces[f][1]], tets[t][TetFaces[f][2]] };
    std::sort(ids.begin(), ids.end());
    return ids;
  };
  // Counting sort of the 4 faces of every tet by their smallest vertex.
  std::vector<std::size_t> start(pointCount + 1, 0);
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (int f = 0; f < 4; ++f)
      ++start[sortedFace(t, f)[0] + 1];
  for (std::size_t p = 0; p < pointCount; ++p)
    start[p + 1] += start[p];
  std::vector<Entry> entries(start[pointCount]);
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (int f = 0; f < 4; ++f)
    {
      const auto ids = sortedFace(t, f);
      entries[fill[ids[0]]++] = Entry{ ids[1], ids[2], static_cast<std::int64_t>(t) };
    }

  // Sorted buckets, then the distinct faces counted, so the list is allocated once.
  std::size_t distinct = 0;
  for (std::size_t a = 0; a < pointCount; ++a)
  {
    const auto first = entries.begin() + start[a];
    const auto last = entries.begin() + start[a + 1];
    std::sort(first, last);
    for (auto it = first; it != last; ++it)
    {
      distinct += it == first || it->B != (it - 1)->B || it->C != (it - 1)->C;
    }
  }
  std::vector<MeshFace> faces;
  faces.reserve(distinct);
  for (std::size_t a = 0; a < pointCount; ++a)
  {
    const auto first = entries.begin() + start[a];
    const auto last = entries.begin() + start[a + 1];
    for (auto it = first; it != last;)
    {
      MeshFace face;
      face.Points = { static_cast<PointId>(a), it->B, it->C };
      auto next = it;
      for (; next != last && next->B == it->B && next->C == it->C; ++next)
      {
        if (face.TetCount < 2)
        {
          face.Tets[face.TetCount] = next->Tet;
        }
        ++face.TetCount;
      }
      faces.push_back(face);
      it = next;
    }
  }
  return faces;
}

std::vector<std::array<std::int64_t, 4>> FaceNeighbours(const std::vector<Tet>& tets, std::size_t pointCount)
{
  std::vector<std::array<std::int64_t, 4>> across(tets.size(), { -1, -1, -1, -1 });
  for (const MeshFace& face : FindMeshFaces(tets, pointCount))
  {
    if (face.TetCount != 2)
    {
      continue;
    }
    for (int side = 0; side < 2; ++side)
    {
      const Tet& tet = tets[face.Tets[side]];
      for (int i = 0; i < 4; ++i)
      {
        if (std::find(face.Points.begin(), face.Points.end(), tet[i]) == face.Points.end())
        {
          across[face.Tets[side]][i] = face.Tets[1 - side];
        }
      }
    }
  }
  return across;
}
} // namespace cbc3d
