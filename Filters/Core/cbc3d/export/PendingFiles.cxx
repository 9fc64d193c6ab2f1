#include "cbc3d/export/PendingFiles.h"

#include <array>
#include <atomic>
#include <cstring>
#include <unistd.h>

namespace cbc3d
{
namespace PendingFiles
{
namespace
{
constexpr int SlotCount = 64;
constexpr std::size_t PathCapacity = 4096;

// A slot is free (0), being filled (1) or holding a path (2); lock-free atomics are safe to read
// from a signal handler, and the path is written before the slot is marked as holding it.
struct Slot
{
  std::atomic<int> State{ 0 };
  char Path[PathCapacity];
};
std::array<Slot, SlotCount> Table;
std::atomic<bool> Hold{ false };
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");
} // namespace

int Add(const std::string& path)
{
  if (path.empty() || path.size() >= PathCapacity)
  {
    return -1;
  }
  for (int s = 0; s < SlotCount; ++s)
  {
    int expected = 0;
    if (Table[s].State.compare_exchange_strong(expected, 1))
    {
      std::memcpy(Table[s].Path, path.c_str(), path.size() + 1);
      Table[s].State.store(2);
      return s;
    }
  }
  return -1;
}

void Forget(int slot)
{
  if (slot >= 0 && slot < SlotCount)
  {
    Table[slot].State.store(0);
  }
}

void RemoveAll() noexcept
{
  for (Slot& slot : Table)
  {
    int holding = 2;
    if (slot.State.compare_exchange_strong(holding, 1))
    {
      unlink(slot.Path);
      slot.State.store(0);
    }
  }
}

void ForgetAll() noexcept
{
  for (Slot& slot : Table)
  {
    int holding = 2;
    slot.State.compare_exchange_strong(holding, 0);
  }
}

void HoldFinishedFiles(bool hold)
{
  Hold.store(hold);
}

bool HoldingFinishedFiles()
{
  return Hold.load();
}
} // namespace PendingFiles
} // namespace cbc3d
