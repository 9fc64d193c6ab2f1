#ifndef cbc3d_StopRequests_h
#define cbc3d_StopRequests_h

#include "cbc3d/base/Progress.h"

#include <functional>

namespace cbc3d
{
/// Setting up and every iteration take seconds on large meshes: a stop request is looked for
/// between the steps, and inside the longest ones through KeepGoing() (reporting the fraction
/// last reached). A stop, once seen, is kept: a step cut short is never used.
class StopRequests
{
public:
  explicit StopRequests(const Progress& progress)
    : Report(progress)
  {
  }
  bool Stopped(double fraction)
  {
    this->Reached = fraction;
    this->Stop = this->Stop || !cbc3d::KeepGoing(this->Report, fraction);
    return this->Stop;
  }
  bool Stopped() const { return this->Stop; }
  const std::function<bool()> KeepGoing = [this] { return !this->Stopped(this->Reached); };

private:
  const Progress& Report;
  bool Stop = false;
  double Reached = 0.0;
};
} // namespace cbc3d

#endif
