#include "cbc3d/deformation/VolumeAims.h"

#include <algorithm>
#include <cmath>

namespace cbc3d
{
VolumeAims::VolumeAims(const std::map<std::int32_t, double>& targets)
  : Targets(targets)
{
}

std::map<std::int32_t, double> VolumeAims::Aims(const std::map<std::int32_t, double>& volumes) const
{
  std::map<std::int32_t, double> aims;
  for (const auto& [label, target] : this->Targets)
  {
    const auto volume = volumes.find(label);
    if (volume == volumes.end() || !(target > 0.0))
      continue;
    const auto gain = this->Gains.find(label);
    const bool near = std::abs(target - volume->second) <= GainedShortfall * target;
    const double factor = near || gain == this->Gains.end() ? 1.0 : gain->second;
    // The target itself, not volume + (target - volume), where there is no gain: the same bits.
    aims[label] = factor == 1.0 ? target : volume->second + factor * (target - volume->second);
  }
  return aims;
}

void VolumeAims::Observe(const std::map<std::int32_t, double>& before, const std::map<std::int32_t, double>& aims,
  const std::map<std::int32_t, double>& after)
{
  for (const auto& [label, aim] : aims)
  {
    const auto from = before.find(label), to = after.find(label);
    if (from == before.end() || to == after.end())
      continue;
    const double asked = aim - from->second, got = to->second - from->second;
    // A round that went the wrong way, or nowhere, teaches nothing: back to the plain shortfall.
    this->Gains[label] = asked != 0.0 && got / asked > 0.0 ? std::clamp(asked / got, 1.0, LargestGain) : 1.0;
  }
}
} // namespace cbc3d
