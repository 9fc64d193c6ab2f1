#include "ThreadWaits.h"

#include <cstdlib>

bool ShortenThreadWaits()
{
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT"))
  {
    return false; // the user's choice stands
  }
  return setenv("GOMP_SPINCOUNT", ShortSpinCount, 1) == 0;
}
