#include "cbc3d/refinement/SurfaceEars.h"


namespace cbc3d
{
std::size_t RemoveSurfaceEars(const std::vector<Tet>& tets,
  const std::vector<TetNeighbours>& across, std::size_t pointCount,
  std::vector<std::int32_t>& labels, const std::function<bool(std::int32_t)>& isTissue,
  std::int32_t removed)
{
  std::size_t relabelled = 0;
  for (bool changed = true; changed;)
  {
    changed = false;
    std::vector<int> uses(pointCount, 0);
    for (std::size_t t = 0; t < tets.size(); ++t)
      if (isTissue(labels[t]))
        for (const PointId p : tets[t])
          ++uses[p];
    for (std::size_t t = 0; t < tets.size(); ++t)
    {
      if (!isTissue(labels[t]))
      {
        continue;
      }
      for (int tip = 0; tip < 4; ++tip)
      {
        if (uses[tets[t][tip]] != 1)
        {
          continue;
        }
        const std::int64_t other = across[t][tip]; // the tet on the base
        if (other >= 0 && labels[other] == labels[t])
        {
          labels[t] = removed;
          for (const PointId p : tets[t])
            --uses[p];
          ++relabelled;
          changed = true;
          break;
        }
      }
    }
  }
  return relabelled;
}
} // namespace cbc3d
