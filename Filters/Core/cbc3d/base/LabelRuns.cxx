#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/Parallel.h"

#include <numeric>

namespace cbc3d
{
// Each thread takes one contiguous block of rows and lists its runs on its own, so the labels
// are read once; the blocks' lists are then joined in row order.
void IndexLabelRuns(LabelImage& image, int numberOfThreads)
{
  const auto& n = image.StoredDimensions();
  const std::int64_t rows = std::int64_t(n[1]) * n[2];
  const int threads = static_cast<int>(
    std::min<std::int64_t>(ThreadCount(numberOfThreads), std::max<std::int64_t>(rows, 1)));
  std::vector<std::vector<std::int32_t>> blockStarts(threads), blockLabels(threads);
  std::vector<std::int64_t> runsPerRow(rows);
  RegionErrors errors; // the blocks' lists grow
#pragma omp parallel for schedule(static, 1) num_threads(threads)
  for (int block = 0; block < threads; ++block)
  {
    errors.Run([&] {
      std::vector<std::int32_t>& starts = blockStarts[block];
      std::vector<std::int32_t>& labels = blockLabels[block];
      for (std::int64_t r = rows * block / threads; r < rows * (block + 1) / threads && !errors.Failed(); ++r)
      {
        const std::int32_t* row = image.Labels.data() + r * n[0];
        const std::size_t before = starts.size();
        starts.push_back(0);
        labels.push_back(row[0]);
        for (int x = 1; x < n[0]; ++x)
        {
          if (row[x] != row[x - 1])
          {
            starts.push_back(x);
            labels.push_back(row[x]);
          }
        }
        runsPerRow[r] = static_cast<std::int64_t>(starts.size() - before);
      }
    });
  }
  errors.Rethrow();
  image.RowRunFirst.assign(rows + 1, 0);
  std::partial_sum(runsPerRow.begin(), runsPerRow.end(), image.RowRunFirst.begin() + 1);
  image.RunStart.clear();
  image.RunLabel.clear();
  image.RunStart.reserve(static_cast<std::size_t>(image.RowRunFirst.back()));
  image.RunLabel.reserve(static_cast<std::size_t>(image.RowRunFirst.back()));
  for (int block = 0; block < threads; ++block)
  {
    image.RunStart.insert(image.RunStart.end(), blockStarts[block].begin(), blockStarts[block].end());
    image.RunLabel.insert(image.RunLabel.end(), blockLabels[block].begin(), blockLabels[block].end());
  }
}
} // namespace cbc3d
