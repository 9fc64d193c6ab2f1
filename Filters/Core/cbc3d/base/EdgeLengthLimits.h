#ifndef cbc3d_EdgeLengthLimits_h
#define cbc3d_EdgeLengthLimits_h

#include <algorithm>
#include <cstdint>
#include <map>

namespace cbc3d
{
/// The longest edge a tet of a tissue may have (mm): one limit for every tissue and limits of
/// single tissues in its place. Refinement splits until the tets keep them; deformation moves
/// no point so that a tet passes its limit.
struct EdgeLengthLimits
{
  double All = 0.0;                       // every tissue without a limit of its own; 0 = none
  std::map<std::int32_t, double> ByTissue; // label -> mm

  /// The limit of a tissue; 0 = none.
  double Of(std::int32_t label) const
  {
    const auto found = this->ByTissue.find(label);
    return found == this->ByTissue.end() ? this->All : found->second;
  }
  /// Whether any tissue has a limit.
  bool Any() const
  {
    return this->All > 0.0 ||
      std::any_of(this->ByTissue.begin(), this->ByTissue.end(), [](const auto& entry) { return entry.second > 0.0; });
  }
};
} // namespace cbc3d

#endif
