#ifndef cbc3d_VolumeAims_h
#define cbc3d_VolumeAims_h

#include <cstdint>
#include <map>

namespace cbc3d
{
/// What each tissue aims at in the rounds that restore the tissues' volumes.
///
/// A round asks every tissue for its shortfall, to first order, and gets only part of it where
/// the guards hold points back: the k-means head's smallest tissue (60 specks) got about half
/// of each round's step, round after round, and took eight rounds of the whole mesh. So a tissue
/// that got part of what it asked for asks that much more in the next round: its shortfall times
/// what it asked over what it got, at most LargestGain times, never less than the shortfall.
/// Within GainedShortfall of its target a tissue asks for the plain shortfall: there the rounds'
/// yields are erratic (tissues share interfaces). Plain arithmetic: the same for any threads.
class VolumeAims
{
public:
  static constexpr double LargestGain = 2.0;
  static constexpr double GainedShortfall = 1e-2; // relative to the target

  /// `targets`: each tissue's volume to reach (mm^3); tissues without one, or with none above
  /// zero, are free.
  explicit VolumeAims(const std::map<std::int32_t, double>& targets);

  /// The volume each tissue with a target should aim at in this round, given its `volumes` now.
  std::map<std::int32_t, double> Aims(const std::map<std::int32_t, double>& volumes) const;

  /// Learns from a round that aimed at `aims` starting from `before` and ended at `after`.
  void Observe(const std::map<std::int32_t, double>& before, const std::map<std::int32_t, double>& aims,
    const std::map<std::int32_t, double>& after);

private:
  const std::map<std::int32_t, double>& Targets;
  std::map<std::int32_t, double> Gains; // per tissue: how many times its shortfall to ask for
};
} // namespace cbc3d

#endif
