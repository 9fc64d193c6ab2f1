#include "cbc3d/quality/MeshTopology.h"

#include "cbc3d/base/DisjointSets.h"
#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/Parallel.h"

#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>

namespace cbc3d
{
namespace
{
// Region 0 is the whole body, region 1 + i the i-th tissue label in ascending order.
constexpr int WholeRegion = 0;

// Values grouped by a key in 0..keyCount-1 (a counting sort): key k's values are
// Values[Start[k]] .. Values[Start[k + 1] - 1]. `forEach(emit)` calls emit(key, value) for
// every pair, the same pairs each time (it runs twice: count, then fill).
template <typename Value>
struct Buckets
{
  std::vector<std::size_t> Start;
  std::vector<Value> Values;
};

template <typename Value, typename ForEach>
Buckets<Value> BucketBy(std::size_t keyCount, ForEach forEach)
{
  Buckets<Value> buckets;
  buckets.Start.assign(keyCount + 1, 0);
  forEach([&buckets](std::size_t key, const Value&) { ++buckets.Start[key + 1]; });
  std::partial_sum(buckets.Start.begin(), buckets.Start.end(), buckets.Start.begin());
  buckets.Values.resize(buckets.Start[keyCount]);
  std::vector<std::size_t> fill(buckets.Start.begin(), buckets.Start.end() - 1);
  forEach([&](std::size_t key, const Value& value) { buckets.Values[fill[key]++] = value; });
  return buckets;
}

// One thread's share of a count per point: its own counts per region, and scratch for a
// vertex's fans.
struct ThreadCounts
{
  std::vector<RegionTopology> Regions;
  std::vector<std::array<PointId, 2>> Others;
  std::vector<std::pair<PointId, std::int64_t>> Scratch;
};

// Runs `countAt(p, counts)` for every point p on `threads`, each thread with its own counts,
// then adds them up: whole numbers, the same for any threads. An exception in a thread (out of
// memory) is thrown again here.
template <typename CountAt>
void CountPerPoint(std::size_t pointCount, int threads, std::vector<RegionTopology>& regions, const CountAt& countAt)
{
  const std::int64_t count = static_cast<std::int64_t>(pointCount);
  std::vector<ThreadCounts> local(static_cast<std::size_t>(threads));
  RegionErrors errors;
#pragma omp parallel num_threads(threads)
  {
    ThreadCounts& mine = local[ThreadId()];
    errors.Run([&] { mine.Regions.resize(regions.size()); });
#pragma omp for schedule(dynamic, 4096)
    for (std::int64_t p = 0; p < count; ++p)
      errors.Run([&] { countAt(static_cast<std::size_t>(p), mine); });
  }
  errors.Rethrow();
  for (const ThreadCounts& counts : local)
    for (std::size_t r = 0; r < regions.size(); ++r)
    {
      regions[r].SurfaceEuler += counts.Regions[r].SurfaceEuler;
      regions[r].NonManifoldEdges += counts.Regions[r].NonManifoldEdges;
      regions[r].NonManifoldVertices += counts.Regions[r].NonManifoldVertices;
    }
}

// A triangle of one region's surface, its vertices ascending.
struct SurfaceTriangle
{
  std::array<PointId, 3> Points;
  int Region;
};

// Face components of every region: tets joined through interior faces, for a tissue only
// when both tets are of it.
void CountFaceComponents(const std::vector<MeshFace>& faces, const std::vector<int>& regionOfTet,
  std::vector<RegionTopology>& regions)
{
  const std::size_t tets = regionOfTet.size();
  DisjointSets whole(tets), tissue(tets);
  for (const MeshFace& face : faces)
  {
    if (face.TetCount >= 2)
    {
      whole.Join(face.Tets[0], face.Tets[1]);
      if (regionOfTet[face.Tets[0]] == regionOfTet[face.Tets[1]])
      {
        tissue.Join(face.Tets[0], face.Tets[1]);
      }
    }
  }
  for (std::size_t t = 0; t < tets; ++t)
  {
    regions[WholeRegion].FaceComponents += whole.IsRoot(t);
    regions[regionOfTet[t]].FaceComponents += tissue.IsRoot(t);
  }
}

// Vertex components of every region: at each vertex, every tet joins the first tet there (the
// whole body) and the first tet there of its own tissue.
void CountVertexComponents(const TetMesh& mesh, const std::vector<int>& regionOfTet,
  std::vector<RegionTopology>& regions)
{
  const auto tetsAt = BucketBy<std::int64_t>(mesh.Points.size(), [&mesh](auto&& emit) {
    for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
      for (const PointId p : mesh.Tets[t])
        emit(static_cast<std::size_t>(p), static_cast<std::int64_t>(t));
  });
  const std::size_t tets = mesh.Tets.size();
  DisjointSets whole(tets), tissue(tets);
  std::vector<std::int64_t> firstOfRegion(regions.size(), -1);
  std::vector<std::size_t> seenAt(regions.size(), std::size_t(-1)); // the vertex that set it
  for (std::size_t p = 0; p < mesh.Points.size(); ++p)
  {
    for (std::size_t i = tetsAt.Start[p]; i < tetsAt.Start[p + 1]; ++i)
    {
      const std::int64_t t = tetsAt.Values[i];
      whole.Join(tetsAt.Values[tetsAt.Start[p]], t);
      const int region = regionOfTet[t];
      if (seenAt[region] != p)
      {
        seenAt[region] = p;
        firstOfRegion[region] = t;
      }
      tissue.Join(firstOfRegion[region], t);
    }
  }
  for (std::size_t t = 0; t < tets; ++t)
  {
    regions[WholeRegion].VertexComponents += whole.IsRoot(t);
    regions[regionOfTet[t]].VertexComponents += tissue.IsRoot(t);
  }
}

// Every region's surface triangles: a boundary face is in the whole body's surface and its
// tet's tissue's; an interface face is in both its tissues'.
std::vector<SurfaceTriangle> SurfaceTriangles(const std::vector<MeshFace>& faces,
  const std::vector<int>& regionOfTet, std::vector<RegionTopology>& regions)
{
  std::vector<SurfaceTriangle> triangles;
  auto add = [&](const MeshFace& face, int region) {
    triangles.push_back(SurfaceTriangle{ face.Points, region });
    ++regions[region].SurfaceTriangles;
  };
  for (const MeshFace& face : faces)
  {
    if (face.TetCount == 1)
    {
      add(face, WholeRegion);
      add(face, regionOfTet[face.Tets[0]]);
    }
    else if (regionOfTet[face.Tets[0]] != regionOfTet[face.Tets[1]])
    {
      add(face, regionOfTet[face.Tets[0]]);
      add(face, regionOfTet[face.Tets[1]]);
    }
  }
  return triangles;
}

// Distinct surface edges per region (subtracted from the Euler sum) and those in more than two
// of the region's triangles. Edges are bucketed on their smaller vertex.
void CountEdges(const std::vector<SurfaceTriangle>& triangles, std::size_t pointCount, int threads,
  std::vector<RegionTopology>& regions)
{
  using Far = std::pair<PointId, int>; // the larger vertex, the region
  auto edges = BucketBy<Far>(pointCount, [&triangles](auto&& emit) {
    for (const SurfaceTriangle& tri : triangles)
    {
      const auto& p = tri.Points;
      emit(static_cast<std::size_t>(p[0]), Far{ p[1], tri.Region });
      emit(static_cast<std::size_t>(p[0]), Far{ p[2], tri.Region });
      emit(static_cast<std::size_t>(p[1]), Far{ p[2], tri.Region });
    }
  });
  CountPerPoint(pointCount, threads, regions, [&edges](std::size_t p, ThreadCounts& counts) {
    const auto first = edges.Values.begin() + edges.Start[p];
    const auto last = edges.Values.begin() + edges.Start[p + 1];
    std::sort(first, last);
    for (auto run = first; run != last;)
    {
      const auto next = std::find_if(run, last, [run](const Far& e) { return e != *run; });
      RegionTopology& region = counts.Regions[run->second];
      --region.SurfaceEuler;
      region.NonManifoldEdges += (next - run) > 2;
      run = next;
    }
  });
}

// Whether the triangles of one region at vertex `p` form more than one fan. `others` holds,
// for each triangle, its two other vertices; `scratch` is reused between calls.
bool SeveralFans(const std::vector<std::array<PointId, 2>>& others,
  std::vector<std::pair<PointId, std::int64_t>>& scratch)
{
  scratch.clear();
  for (std::size_t i = 0; i < others.size(); ++i)
  {
    scratch.emplace_back(others[i][0], static_cast<std::int64_t>(i));
    scratch.emplace_back(others[i][1], static_cast<std::int64_t>(i));
  }
  // Triangles sharing an other vertex share the edge from p to it.
  std::sort(scratch.begin(), scratch.end());
  DisjointSets fans(others.size());
  for (std::size_t i = 1; i < scratch.size(); ++i)
  {
    if (scratch[i].first == scratch[i - 1].first)
    {
      fans.Join(scratch[i].second, scratch[i - 1].second);
    }
  }
  for (std::size_t i = 1; i < others.size(); ++i)
  {
    if (fans.Find(static_cast<std::int64_t>(i)) != 0)
    {
      return true;
    }
  }
  return false;
}

// Distinct surface vertices per region (added to the Euler sum) and the non-manifold ones.
void CountVertices(const std::vector<SurfaceTriangle>& triangles, std::size_t pointCount, int threads,
  std::vector<RegionTopology>& regions)
{
  using Corner = std::pair<int, std::int64_t>; // region, triangle
  auto corners = BucketBy<Corner>(pointCount, [&triangles](auto&& emit) {
    for (std::size_t t = 0; t < triangles.size(); ++t)
      for (const PointId p : triangles[t].Points)
        emit(static_cast<std::size_t>(p), Corner{ triangles[t].Region, static_cast<std::int64_t>(t) });
  });
  CountPerPoint(pointCount, threads, regions, [&](std::size_t p, ThreadCounts& counts) {
    std::vector<std::array<PointId, 2>>& others = counts.Others;
    const auto first = corners.Values.begin() + corners.Start[p];
    const auto last = corners.Values.begin() + corners.Start[p + 1];
    std::sort(first, last);
    for (auto run = first; run != last;)
    {
      others.clear();
      auto next = run;
      for (; next != last && next->first == run->first; ++next)
      {
        const auto& q = triangles[next->second].Points;
        others.push_back(q[0] == PointId(p) ? std::array<PointId, 2>{ q[1], q[2] }
            : q[1] == PointId(p)            ? std::array<PointId, 2>{ q[0], q[2] }
                                            : std::array<PointId, 2>{ q[0], q[1] });
      }
      RegionTopology& region = counts.Regions[run->first];
      ++region.SurfaceEuler;
      region.NonManifoldVertices += SeveralFans(others, counts.Scratch);
      run = next;
    }
  });
}

// The labels present, ascending; a mesh has few, and its tets come in runs of one label.
std::vector<std::int32_t> DistinctLabels(const std::vector<std::int32_t>& tetLabels)
{
  std::vector<std::int32_t> labels;
  for (std::size_t t = 0; t < tetLabels.size(); ++t)
  {
    if (t > 0 && tetLabels[t] == tetLabels[t - 1])
      continue;
    const auto at = std::lower_bound(labels.begin(), labels.end(), tetLabels[t]);
    if (at == labels.end() || *at != tetLabels[t])
      labels.insert(at, tetLabels[t]);
  }
  return labels;
}
} // namespace

bool MeshTopology::SolverReady() const
{
  return this->Whole.Manifold() &&
    std::all_of(this->Tissues.begin(), this->Tissues.end(),
      [](const std::pair<const std::int32_t, RegionTopology>& tissue) { return tissue.second.Manifold(); });
}

MeshTopology MeasureMeshTopology(const TetMesh& mesh, int numberOfThreads)
{
  return MeasureMeshTopology(mesh, FindMeshFaces(mesh, numberOfThreads), numberOfThreads);
}

MeshTopology MeasureMeshTopology(const TetMesh& mesh, const std::vector<MeshFace>& faces, int numberOfThreads)
{
  const int threads = ThreadCount(numberOfThreads);
  const std::vector<std::int32_t> labels = DistinctLabels(mesh.Labels);
  std::vector<int> regionOfTet(mesh.Tets.size());
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    regionOfTet[t] =
      1 + static_cast<int>(std::lower_bound(labels.begin(), labels.end(), mesh.Labels[t]) - labels.begin());
  }

  std::vector<RegionTopology> regions(1 + labels.size());
  // The two counts fill different figures of the regions: one thread each.
  RegionErrors errors;
#pragma omp parallel sections num_threads(std::min(threads, 2))
  {
#pragma omp section
    errors.Run([&] { CountFaceComponents(faces, regionOfTet, regions); });
#pragma omp section
    errors.Run([&] { CountVertexComponents(mesh, regionOfTet, regions); });
  }
  errors.Rethrow();
  const std::vector<SurfaceTriangle> triangles = SurfaceTriangles(faces, regionOfTet, regions);
  CountEdges(triangles, mesh.Points.size(), threads, regions);
  CountVertices(triangles, mesh.Points.size(), threads, regions);

  MeshTopology topology;
  for (RegionTopology& region : regions)
  {
    region.HingedParts = region.FaceComponents - region.VertexComponents;
    region.SurfaceEuler += region.SurfaceTriangles;
  }
  topology.Whole = regions[WholeRegion];
  for (std::size_t i = 0; i < labels.size(); ++i)
  {
    topology.Tissues[labels[i]] = regions[1 + i];
  }
  return topology;
}
} // namespace cbc3d
