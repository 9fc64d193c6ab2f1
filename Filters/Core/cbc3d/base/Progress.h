#ifndef cbc3d_Progress_h
#define cbc3d_Progress_h

#include <functional>

namespace cbc3d
{
/// Called with the fraction done in [0, 1]; returns false to ask the algorithm to stop.
/// Core loops call it from OpenMP thread 0 only (the thread that entered the loop), so a
/// VTK observer behind it never runs on a worker thread.
using Progress = std::function<bool(double fraction)>;

/// Whether to go on: true unless `progress` is set and asks to stop.
inline bool KeepGoing(const Progress& progress, double fraction)
{
  return !progress || progress(fraction);
}
} // namespace cbc3d

#endif
