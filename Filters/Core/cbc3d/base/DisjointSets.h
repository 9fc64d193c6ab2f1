#ifndef cbc3d_DisjointSets_h
#define cbc3d_DisjointSets_h

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace cbc3d
{
// Disjoint sets over 0..n-1 with path halving; the smaller index becomes the root.
class DisjointSets
{
public:
  explicit DisjointSets(std::size_t count)
    : Parent(count)
  {
    std::iota(this->Parent.begin(), this->Parent.end(), std::int64_t(0));
  }
  std::int64_t Find(std::int64_t x)
  {
    while (this->Parent[x] != x)
    {
      this->Parent[x] = this->Parent[this->Parent[x]];
      x = this->Parent[x];
    }
    return x;
  }
  void Join(std::int64_t a, std::int64_t b)
  {
    a = this->Find(a);
    b = this->Find(b);
    if (a != b)
    {
      this->Parent[std::max(a, b)] = std::min(a, b);
    }
  }
  bool IsRoot(std::int64_t x) const { return this->Parent[x] == x; }

private:
  std::vector<std::int64_t> Parent;
};
} // namespace cbc3d

#endif
