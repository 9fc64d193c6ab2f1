#ifndef cbc3d_PointTets_h
#define cbc3d_PointTets_h

#include "cbc3d/base/TetMesh.h"

#include <cstdint>
#include <vector>

namespace cbc3d
{
/// The tets around each point, in compressed rows: point p's tets, in ascending order, are
/// Tets[Start[p]] .. Tets[Start[p + 1] - 1]. Tet ids take 32 bits: four per tet, they were the
/// largest list that deformation keeps (133 MB of the 1 mm New York Head's 4.2 M tets at 64).
struct PointTets
{
  std::vector<std::int64_t> Start;
  std::vector<std::int32_t> Tets;

  /// Built on `threads` threads (0: all cores), the same lists for any number. Throws
  /// std::length_error for 2^31 tets or more.
  PointTets(const std::vector<Tet>& tets, std::size_t pointCount, int threads = 1);
};
} // namespace cbc3d

#endif
