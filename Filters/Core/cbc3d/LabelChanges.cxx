#include "cbc3d/LabelImage.h"
#include "cbc3d/Parallel.h"

#include <numeric>

namespace cbc3d
{
// Each thread takes one contiguous block of rows and lists its changes on its own, so the
// labels are read once; the blocks' lists are then joined in row order.
void IndexLabelChanges(LabelImage& image, int numberOfThreads)
{
  const auto& n = image.StoredDimensions();
  const std::int64_t rows = std::int64_t(n[1]) * n[2];
  const int threads = static_cast<int>(std::min<std::int64_t>(ThreadCount(numberOfThreads), std::max<std::int64_t>(rows, 1)));
  std::vector<std::vector<std::int32_t>> blockChanges(threads);
  std::vector<std::int64_t> changesPerRow(rows);
#pragma omp parallel for schedule(static, 1) num_threads(threads)
  for (int block = 0; block < threads; ++block)
  {
    std::vector<std::int32_t>& changes = blockChanges[block];
    for (std::int64_t r = rows * block / threads; r < rows * (block + 1) / threads; ++r)
    {
      const std::int32_t* row = image.Labels.data() + r * n[0];
      const std::size_t before = changes.size();
      for (int x = 1; x < n[0]; ++x)
      {
        if (row[x] != row[x - 1])
          changes.push_back(x);
      }
      changesPerRow[r] = static_cast<std::int64_t>(changes.size() - before);
    }
  }
  image.RowChangeStart.assign(rows + 1, 0);
  std::partial_sum(changesPerRow.begin(), changesPerRow.end(), image.RowChangeStart.begin() + 1);
  image.RowChanges.clear();
  image.RowChanges.reserve(static_cast<std::size_t>(image.RowChangeStart.back()));
  for (const auto& changes : blockChanges)
  {
    image.RowChanges.insert(image.RowChanges.end(), changes.begin(), changes.end());
  }
}
} // namespace cbc3d
