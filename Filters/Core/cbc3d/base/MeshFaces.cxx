#include "cbc3d/base/MeshFaces.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/PointTets.h"

#include <algorithm>
#include <functional>
#include <memory>

namespace cbc3d
{
namespace
{
/// A face by its two larger vertices (its smallest is its bucket), and one tet using it: 12
/// bytes, four a tet (with 64-bit ids they took 16: 266 MB of the 1 mm New York Head's peak).
struct FaceEntry
{
  std::uint32_t Second, Third;
  std::int32_t Tet;
  bool SameFace(const FaceEntry& other) const { return this->Second == other.Second && this->Third == other.Third; }
  bool operator<(const FaceEntry& other) const
  {
    return this->Second != other.Second ? this->Second < other.Second
      : this->Third != other.Third      ? this->Third < other.Third
                                        : this->Tet < other.Tet;
  }
};

std::array<PointId, 4> SortedCorners(const Tet& tet)
{
  std::array<PointId, 4> ids = tet;
  // A sorting network of five compare-exchanges.
  auto order = [&ids](int i, int j) {
    if (ids[j] < ids[i])
    {
      std::swap(ids[i], ids[j]);
    }
  };
  order(0, 1);
  order(2, 3);
  order(0, 2);
  order(1, 3);
  order(1, 2);
  return ids;
}

/// The identity, for BucketFaces over every tet.
constexpr auto EveryTet = [](std::int64_t i) { return i; };

/// Every face of every tet in buckets by its smallest vertex (bucket a holds entries
/// start[a]..start[a+1]), each bucket sorted, so the order never depends on the threads.
struct FaceBuckets
{
  std::vector<std::size_t> Start;
  std::unique_ptr<FaceEntry[]> Entries; // not zeroed: the threads' fill touches it first

  /// Calls `emit` with each distinct face of bucket `a`, in order.
  template <typename Emit>
  void ForEachFace(std::size_t a, Emit&& emit) const
  {
    const FaceEntry* entries = this->Entries.get();
    for (std::size_t e = this->Start[a]; e < this->Start[a + 1];)
    {
      MeshFace face;
      face.Points = { static_cast<PointId>(a), static_cast<PointId>(entries[e].Second),
        static_cast<PointId>(entries[e].Third) };
      const FaceEntry& first = entries[e];
      for (; e < this->Start[a + 1] && entries[e].SameFace(first); ++e)
      {
        if (face.TetCount < 2)
        {
          face.Tets[face.TetCount] = entries[e].Tet;
        }
        ++face.TetCount;
      }
      emit(face);
    }
  }
};

/// Buckets the faces of tets[tetOf(i)] for i = 0 .. count - 1 (`tetOf` ascending), each entry
/// naming its tet by its id in `tets`.
template <typename TetOf>
FaceBuckets BucketFaces(const std::vector<Tet>& tets, std::int64_t tetCount, const TetOf& tetOf,
  std::uint64_t pointCount, int threads)
{
  CheckPointCount(pointCount); // the entries hold 32-bit ids
  CheckTetCount(tets.size());
  // Faces of a tet with sorted corners a < b < c < d: bcd, acd, abd, abc.
  FaceBuckets buckets;
  buckets.Start.assign(pointCount + 1, 0);
  std::size_t* start = buckets.Start.data();
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t i = 0; i < tetCount; ++i)
  {
    const auto ids = SortedCorners(tets[tetOf(i)]);
#pragma omp atomic
    start[ids[0] + 1] += 3;
#pragma omp atomic
    start[ids[1] + 1] += 1;
  }
  for (std::uint64_t p = 0; p < pointCount; ++p)
  {
    start[p + 1] += start[p];
  }
  buckets.Entries.reset(new FaceEntry[start[pointCount]]);
  std::vector<std::size_t> fill(buckets.Start.begin(), buckets.Start.end() - 1);
  std::size_t* next = fill.data();
  FaceEntry* entries = buckets.Entries.get();
  auto put = [&](PointId a, PointId b, PointId c, std::int64_t t) {
    std::size_t slot;
#pragma omp atomic capture
    slot = next[a]++;
    entries[slot] =
      FaceEntry{ static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(c), static_cast<std::int32_t>(t) };
  };
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t i = 0; i < tetCount; ++i)
  {
    const std::int64_t t = tetOf(i);
    const auto ids = SortedCorners(tets[t]);
    put(ids[1], ids[2], ids[3], t);
    put(ids[0], ids[2], ids[3], t);
    put(ids[0], ids[1], ids[3], t);
    put(ids[0], ids[1], ids[2], t);
  }
  // Threads fill a bucket in any order: sorting it makes the order the same for any count.
  const std::int64_t bucketCount = static_cast<std::int64_t>(pointCount);
#pragma omp parallel for schedule(dynamic, 4096) num_threads(threads)
  for (std::int64_t a = 0; a < bucketCount; ++a)
  {
    std::sort(entries + start[a], entries + start[a + 1]);
  }
  return buckets;
}

/// The faces that `keep` holds for, in bucket order: each bucket counts its kept faces, then
/// writes them from its own offset, so the list is the same for any number of threads.
template <typename Keep>
std::vector<MeshFace> CollectFaces(const FaceBuckets& buckets, std::uint64_t pointCount, int threads, const Keep& keep)
{
  const std::int64_t bucketCount = static_cast<std::int64_t>(pointCount);
  std::vector<std::size_t> firstFace(pointCount + 1, 0);
#pragma omp parallel for schedule(dynamic, 4096) num_threads(threads)
  for (std::int64_t a = 0; a < bucketCount; ++a)
  {
    buckets.ForEachFace(a, [&](const MeshFace& face) { firstFace[a + 1] += keep(face) ? 1 : 0; });
  }
  for (std::size_t a = 0; a < pointCount; ++a)
  {
    firstFace[a + 1] += firstFace[a];
  }
  std::vector<MeshFace> faces(firstFace[pointCount]);
#pragma omp parallel for schedule(dynamic, 4096) num_threads(threads)
  for (std::int64_t a = 0; a < bucketCount; ++a)
  {
    std::size_t next = firstFace[a];
    buckets.ForEachFace(a, [&](const MeshFace& face) {
      if (keep(face))
      {
        faces[next++] = face;
      }
    });
  }
  return faces;
}
} // namespace

std::vector<MeshFace> FindMeshFaces(const std::vector<Tet>& tets, std::size_t pointCount, int numberOfThreads)
{
  const int threads = ThreadCount(numberOfThreads);
  const FaceBuckets buckets = BucketFaces(tets, static_cast<std::int64_t>(tets.size()), EveryTet, pointCount, threads);
  return CollectFaces(buckets, pointCount, threads, [](const MeshFace&) { return true; });
}

std::vector<MeshFace> SelectMeshFaces(const std::vector<Tet>& tets, std::size_t pointCount, int numberOfThreads,
  const std::function<bool(const MeshFace&)>& keep)
{
  const int threads = ThreadCount(numberOfThreads);
  const FaceBuckets buckets = BucketFaces(tets, static_cast<std::int64_t>(tets.size()), EveryTet, pointCount, threads);
  return CollectFaces(buckets, pointCount, threads, keep);
}

std::vector<MeshFace> SelectMeshFaces(const std::vector<Tet>& tets, const std::vector<std::int32_t>& subset,
  std::size_t pointCount, int numberOfThreads, const std::function<bool(const MeshFace&)>& keep)
{
  const int threads = ThreadCount(numberOfThreads);
  const auto tetOf = [&subset](std::int64_t i) { return std::int64_t(subset[i]); };
  return CollectFaces(BucketFaces(tets, static_cast<std::int64_t>(subset.size()), tetOf, pointCount, threads),
    pointCount, threads, keep);
}

std::vector<MeshFace> SurfaceFaces(const TetMesh& mesh, int numberOfThreads)
{
  return SelectMeshFaces(mesh.Tets, mesh.Points.size(), numberOfThreads, [&](const MeshFace& face) {
    return face.TetCount != 2 || mesh.Labels[face.Tets[0]] != mesh.Labels[face.Tets[1]];
  });
}

std::vector<TetNeighbours> FaceNeighbours(
  const std::vector<Tet>& tets, std::size_t pointCount, int numberOfThreads)
{
  // Found through the tets around each point (16 bytes a tet), not from buckets of every face
  // (48 bytes a tet, held beside the answer: the peak of the 1 mm New York Head's refinement).
  const int threads = ThreadCount(numberOfThreads);
  const PointTets around(tets, pointCount, threads);
  std::vector<TetNeighbours> across(tets.size(), { -1, -1, -1, -1 });
  const std::int64_t tetCount = static_cast<std::int64_t>(tets.size());
  const auto aroundCount = [&around](PointId p) { return around.Start[p + 1] - around.Start[p]; };
  const auto holds = [](const Tet& tet, PointId p) {
    return (tet[0] == p) | (tet[1] == p) | (tet[2] == p) | (tet[3] == p);
  };
#pragma omp parallel for schedule(dynamic, 4096) num_threads(threads)
  for (std::int64_t t = 0; t < tetCount; ++t)
  {
    for (int i = 0; i < 4; ++i)
    {
      // The face opposite corner i, searched among the tets around its corner with the fewest
      // (each of them holds that corner); it has a neighbour across when exactly one other tet
      // holds its other two corners too (more: the mesh does not conform).
      std::array<PointId, 3> face = { tets[t][(i + 1) % 4], tets[t][(i + 2) % 4], tets[t][(i + 3) % 4] };
      const int least = aroundCount(face[0]) <= aroundCount(face[1])
        ? (aroundCount(face[0]) <= aroundCount(face[2]) ? 0 : 2)
        : (aroundCount(face[1]) <= aroundCount(face[2]) ? 1 : 2);
      std::swap(face[0], face[least]);
      int others = 0;
      std::int64_t other = -1;
      for (std::int64_t k = around.Start[face[0]]; k < around.Start[face[0] + 1]; ++k)
      {
        const std::int64_t u = around.Tets[k];
        if (u != t && holds(tets[u], face[1]) && holds(tets[u], face[2]))
        {
          ++others;
          other = u;
        }
      }
      across[t][i] = others == 1 ? std::int32_t(other) : -1;
    }
  }
  return across;
}
} // namespace cbc3d
