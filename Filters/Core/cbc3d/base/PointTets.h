#ifndef cbc3d_PointTets_h
#define cbc3d_PointTets_h

#include "cbc3d/base/TetMesh.h"

#include <cstdint>
#include <limits>
#include <stdexcept>
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

  PointTets(const std::vector<Tet>& tets, std::size_t pointCount)
    : Start(pointCount + 1, 0)
  {
    if (tets.size() > std::size_t(std::numeric_limits<std::int32_t>::max()))
    {
      throw std::length_error("a mesh of more than 2^31 - 1 tets: mesh it in pieces (over MPI ranks)");
    }
    for (const Tet& tet : tets)
      for (const PointId p : tet)
        ++this->Start[p + 1];
    for (std::size_t p = 0; p < pointCount; ++p)
      this->Start[p + 1] += this->Start[p];
    this->Tets.resize(this->Start[pointCount]);
    std::vector<std::int64_t> fill(this->Start.begin(), this->Start.end() - 1);
    for (std::size_t t = 0; t < tets.size(); ++t)
      for (const PointId p : tets[t])
        this->Tets[fill[p]++] = static_cast<std::int32_t>(t);
  }
};
} // namespace cbc3d

#endif
