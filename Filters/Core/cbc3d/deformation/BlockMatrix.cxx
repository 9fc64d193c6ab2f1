#include "cbc3d/deformation/BlockMatrix.h"

#include "cbc3d/base/Parallel.h"

#include <algorithm>

namespace cbc3d
{
void BlockMatrix::Multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y, int threads) const
{
  const std::int64_t n = static_cast<std::int64_t>(this->Points());
  y.resize(this->Size());
  const double* in = x.data();
  double* out = y.data();
#pragma omp parallel for schedule(dynamic, 1024) num_threads(ThreadCount(threads))
  for (std::int64_t p = 0; p < n; ++p)
  {
    // The three rows of p side by side: each block's nine values are read once, in order.
    double sum[3] = { 0.0, 0.0, 0.0 };
    for (std::int64_t k = this->RowStart[p]; k < this->RowStart[p + 1]; ++k)
    {
      const float* block = this->Values.data() + 9 * k;
      const double* near = in + 3 * std::int64_t(this->Columns[k]);
      for (int c = 0; c < 3; ++c)
      {
        for (int r = 0; r < 3; ++r)
        {
          sum[c] += double(block[3 * c + r]) * near[r];
        }
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      out[3 * p + c] = sum[c] + this->Diagonal[3 * p + c] * in[3 * p + c];
    }
  }
}

double BlockMatrix::Coefficient(Eigen::Index row, Eigen::Index column) const
{
  if (row == column)
  {
    return this->Diagonal[row];
  }
  const std::int64_t p = row / 3, q = column / 3;
  const auto first = this->Columns.begin() + this->RowStart[p];
  const auto last = this->Columns.begin() + this->RowStart[p + 1];
  const auto found = std::lower_bound(first, last, q);
  if (found == last || *found != q)
  {
    return 0.0;
  }
  const std::int64_t k = found - this->Columns.begin();
  return this->Values[9 * k + 3 * (row % 3) + column % 3];
}
} // namespace cbc3d
