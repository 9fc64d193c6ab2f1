#include "cbc3d/InteriorSmoothing.h"

#include "cbc3d/TetGeometry.h"

#include <algorithm>

namespace cbc3d
{
InteriorSmoothing::InteriorSmoothing(const std::vector<Tet>& tets, std::size_t pointCount)
  : Tets(tets)
  , Around(tets, pointCount)
{
}

std::size_t InteriorSmoothing::Smooth(
  std::vector<Eigen::Vector3d>& x, const std::vector<char>& movable, int sweeps) const
{
  // The worst tet around p, as the largest dihedral |cos| (2 when one is inverted).
  auto worst = [&](std::size_t p) {
    double w = 0.0;
    for (std::int64_t i = this->Around.Start[p]; i < this->Around.Start[p + 1]; ++i)
    {
      const Tet& t = this->Tets[this->Around.Tets[i]];
      w = std::max(w, SignedVolume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]) > 0.0
          ? LargestDihedralCosine(x[t[0]], x[t[1]], x[t[2]], x[t[3]])
          : 2.0);
    }
    return w;
  };
  std::size_t moves = 0;
  for (int sweep = 0; sweep < sweeps; ++sweep)
  {
    std::size_t moved = 0;
    for (std::size_t p = 0; p + 1 < this->Around.Start.size(); ++p)
    {
      if (!movable[p] || this->Around.Start[p] == this->Around.Start[p + 1])
      {
        continue;
      }
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (std::int64_t i = this->Around.Start[p]; i < this->Around.Start[p + 1]; ++i)
        for (const PointId q : this->Tets[this->Around.Tets[i]])
          centre += x[q];
      centre /= 4.0 * double(this->Around.Start[p + 1] - this->Around.Start[p]);
      const double before = worst(p);
      const Eigen::Vector3d kept = x[p];
      x[p] = centre;
      if (worst(p) < before)
      {
        ++moved;
      }
      else
      {
        x[p] = kept;
      }
    }
    moves += moved;
    if (moved == 0)
    {
      break;
    }
  }
  return moves;
}
} // namespace cbc3d
