#ifndef cbc3d_PointTets_h
#define cbc3d_PointTets_h

#include "cbc3d/base/TetMesh.h"

#include <cstdint>
#include <vector>

namespace cbc3d
{
/// The tets around each point, in compressed rows: point p's tets, in ascending order, are
/// Tets[Start[p]] .. Tets[Start[p + 1] - 1].
struct PointTets
{
  std::vector<std::int64_t> Start, Tets;

  PointTets(const std::vector<Tet>& tets, std::size_t pointCount)
    : Start(pointCount + 1, 0)
  {
    for (const Tet& tet : tets)
      for (const PointId p : tet)
        ++this->Start[p + 1];
    for (std::size_t p = 0; p < pointCount; ++p)
      this->Start[p + 1] += this->Start[p];
    this->Tets.resize(this->Start[pointCount]);
    std::vector<std::int64_t> fill(this->Start.begin(), this->Start.end() - 1);
    for (std::size_t t = 0; t < tets.size(); ++t)
      for (const PointId p : tets[t])
        this->Tets[fill[p]++] = static_cast<std::int64_t>(t);
  }
};
} // namespace cbc3d

#endif
