#include "cbc3d/quality/Quality.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/TetGeometry.h"
#include "cbc3d/sampling/TetVoxelSampler.h"

#include <algorithm>
#include <vector>

namespace cbc3d
{
void DihedralSummary::Merge(const DihedralSummary& other)
{
  this->Tets += other.Tets;
  this->MinDegrees = std::min(this->MinDegrees, other.MinDegrees);
  this->MaxDegrees = std::max(this->MaxDegrees, other.MaxDegrees);
  this->Inverted += other.Inverted;
  this->SmallAngle += other.SmallAngle;
  this->LargeAngle += other.LargeAngle;
}

QualitySummary SummarizeQuality(const TetMesh& mesh, int numberOfThreads,
  TetDihedralExtremes* perTet)
{
  const int threads = ThreadCount(numberOfThreads);
  std::vector<std::map<std::int32_t, DihedralSummary>> perThread(threads);
  const std::int64_t count = static_cast<std::int64_t>(mesh.Tets.size());
  if (perTet)
  {
    perTet->MinDegrees.resize(count);
    perTet->MaxDegrees.resize(count);
  }
  RegionErrors errors; // a label's first tet on a thread adds to its map
#pragma omp parallel num_threads(threads)
  {
    auto& local = perThread[ThreadId()];
#pragma omp for schedule(static)
    for (std::int64_t t = 0; t < count; ++t)
    {
      if (errors.Failed())
        continue;
      const Tet& tet = mesh.Tets[t];
      const auto& p = mesh.Points;
      const auto angles = DihedralAngles(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]);
      const auto [lo, hi] = std::minmax_element(angles.begin(), angles.end());
      DihedralSummary one;
      one.Tets = 1;
      one.MinDegrees = *lo * RadiansToDegrees;
      one.MaxDegrees = *hi * RadiansToDegrees;
      one.Inverted = SignedVolume(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]) > 0.0 ? 0 : 1;
      one.SmallAngle = one.MinDegrees < SmallAngleDegrees ? 1 : 0;
      one.LargeAngle = one.MaxDegrees > LargeAngleDegrees ? 1 : 0;
      errors.Run([&] { local[mesh.Labels[t]].Merge(one); });
      if (perTet)
      {
        perTet->MinDegrees[t] = one.MinDegrees;
        perTet->MaxDegrees[t] = one.MaxDegrees;
      }
    }
  }
  errors.Rethrow();
  QualitySummary summary;
  for (const auto& local : perThread)
  {
    for (const auto& [label, figures] : local)
    {
      summary.Tissues[label].Merge(figures);
      summary.Overall.Merge(figures);
    }
  }
  return summary;
}

std::map<std::int32_t, double> TissueMeshVolumes(const TetMesh& mesh)
{
  std::map<std::int32_t, double> volumes;
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const Tet& tet = mesh.Tets[t];
    volumes[mesh.Labels[t]] +=
      SignedVolume(mesh.Points[tet[0]], mesh.Points[tet[1]], mesh.Points[tet[2]], mesh.Points[tet[3]]);
  }
  return volumes;
}

namespace
{
// The tissue voxels per label from the index of runs: one step per run, none per voxel.
std::map<std::int32_t, std::int64_t> CountTissueRuns(const LabelImage& image)
{
  LabelCounts counts; // a few labels: a short list beats a map per run
  const std::int64_t rowLength = image.StoredDimensions()[0];
  const std::int64_t rows = static_cast<std::int64_t>(image.RowRunFirst.size()) - 1;
  for (std::int64_t r = 0; r < rows; ++r)
  {
    for (std::int64_t run = image.RowRunFirst[r]; run < image.RowRunFirst[r + 1]; ++run)
    {
      const std::int64_t end = run + 1 < image.RowRunFirst[r + 1] ? image.RunStart[run + 1] : rowLength;
      if (image.IsTissue(image.RunLabel[run]))
        counts.Add(image.RunLabel[run], end - image.RunStart[run]);
    }
  }
  return std::map<std::int32_t, std::int64_t>(counts.Counts.begin(), counts.Counts.end());
}
} // namespace

std::map<std::int32_t, double> TissueImageVolumes(const LabelImage& image, int numberOfThreads)
{
  std::map<std::int32_t, std::int64_t> counts;
  const std::int64_t voxels = static_cast<std::int64_t>(image.Labels.size());
  if (!image.RowRunFirst.empty())
    counts = CountTissueRuns(image);
  else
#pragma omp parallel num_threads(ThreadCount(numberOfThreads))
  {
    // Runs of one label are counted at once: one map update per run, not per voxel.
    std::map<std::int32_t, std::int64_t> local;
    std::int32_t label = 0;
    std::int64_t run = 0;
    auto flush = [&] {
      if (run > 0 && image.IsTissue(label))
        local[label] += run;
    };
#pragma omp for schedule(static) nowait
    for (std::int64_t v = 0; v < voxels; ++v)
    {
      if (run > 0 && image.Labels[v] == label)
      {
        ++run;
        continue;
      }
      flush();
      label = image.Labels[v];
      run = 1;
    }
    flush();
#pragma omp critical
    for (const auto& [tissue, count] : local)
      counts[tissue] += count;
  }
  const double voxelVolume = image.Spacing.prod();
  std::map<std::int32_t, double> volumes;
  for (const auto& [label, count] : counts)
  {
    volumes[label] = double(count) * voxelVolume;
  }
  return volumes;
}
} // namespace cbc3d
