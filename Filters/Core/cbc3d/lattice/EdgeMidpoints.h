#ifndef cbc3d_EdgeMidpoints_h
#define cbc3d_EdgeMidpoints_h

#include "cbc3d/base/TetMesh.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace cbc3d
{
/// The midpoint of each split edge, keyed by the edge's two point ids (`key`: smaller << 32 |
/// larger). An open-addressing hash table with linear probing: std::unordered_map's node per
/// entry made these lookups the main cost of closing and building a red-green mesh.
class EdgeMidpoints
{
public:
  EdgeMidpoints() { this->Resize(1024); }

  /// The midpoint stored for `key`, or -1.
  PointId Find(std::uint64_t key) const
  {
    for (std::size_t slot = this->SlotOf(key);; slot = (slot + 1) & this->Mask)
    {
      if (this->Keys[slot] == key)
      {
        return this->Values[slot];
      }
      if (this->Keys[slot] == Empty)
      {
        return -1;
      }
    }
  }

  /// Stores `point` for `key` unless it has a midpoint already; returns the midpoint stored and
  /// whether it is the new one.
  std::pair<PointId, bool> Insert(std::uint64_t key, PointId point)
  {
    if (2 * (this->Count + 1) > this->Keys.size()) // at most half full: probes stay short
    {
      this->Resize(2 * this->Keys.size());
    }
    std::size_t slot = this->SlotOf(key);
    for (; this->Keys[slot] != Empty; slot = (slot + 1) & this->Mask)
    {
      if (this->Keys[slot] == key)
      {
        return { this->Values[slot], false };
      }
    }
    this->Keys[slot] = key;
    this->Values[slot] = point;
    ++this->Count;
    return { point, true };
  }

  std::size_t Size() const { return this->Count; }

private:
  static constexpr std::uint64_t Empty = ~std::uint64_t{ 0 }; // no edge has this key

  // Fibonacci hashing: the top bits of the key times 2^64 / golden ratio.
  std::size_t SlotOf(std::uint64_t key) const
  {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> this->Shift);
  }

  void Resize(std::size_t capacity) // a power of two
  {
    std::vector<std::uint64_t> keys(capacity, Empty);
    std::vector<PointId> values(capacity, -1);
    this->Keys.swap(keys);
    this->Values.swap(values);
    this->Mask = capacity - 1;
    this->Shift = 64;
    for (std::size_t c = capacity; c > 1; c >>= 1)
    {
      --this->Shift;
    }
    this->Count = 0;
    for (std::size_t i = 0; i < keys.size(); ++i)
    {
      if (keys[i] != Empty)
      {
        this->Insert(keys[i], values[i]);
      }
    }
  }

  std::vector<std::uint64_t> Keys;
  std::vector<PointId> Values;
  std::size_t Count = 0;
  std::size_t Mask = 0;
  int Shift = 64;
};
} // namespace cbc3d

#endif
