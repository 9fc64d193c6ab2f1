#ifndef cbc3d_BlockMatrix_h
#define cbc3d_BlockMatrix_h

#include "cbc3d/base/UninitializedVector.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace cbc3d
{
/// A symmetric sparse matrix of 3x3 blocks over the points of a mesh, in compressed rows: the
/// stiffness of LinearElasticity.h, 3 degrees of freedom per point (x, y, z of point p at
/// 3p..3p+2). Point p's blocks are k = RowStart[p] .. RowStart[p + 1] - 1, each coupling p with
/// point Columns[k] (ascending, p itself among them).
///
/// The entries off the diagonal are stored in single precision,
/// Values[9k + 3c + r] = K(3p + c, 3 Columns[k] + r), and the diagonal in double precision,
/// Diagonal[i] = K(i, i) (Values holds 0 there): springs are added to the diagonal, and the
/// products sum in double. 40 bytes a block, where Eigen's compressed storage of doubles takes
/// 108: the 1 mm New York Head's stiffness takes 0.42 GB, not 1.15 GB.
struct BlockMatrix
{
  std::vector<std::int64_t> RowStart{ 0 };
  std::vector<std::int32_t> Columns;
  UninitializedVector<float> Values; // (filled in parallel: see UninitializedVector.h)
  std::vector<double> Diagonal;

  std::size_t Points() const { return this->RowStart.size() - 1; }
  Eigen::Index Size() const { return static_cast<Eigen::Index>(3 * this->Points()); }
  std::int64_t Blocks() const { return this->RowStart.back(); }

  /// y = K x, on `threads` threads. Each entry is summed over its row's blocks in order, and
  /// within a block over the axes in order, so y is the same for any thread count.
  void Multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y, int threads) const;

  /// K(row, column), 0 outside the pattern; finds the block by a binary search.
  double Coefficient(Eigen::Index row, Eigen::Index column) const;
};
} // namespace cbc3d

#endif
