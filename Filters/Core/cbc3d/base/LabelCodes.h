#ifndef cbc3d_LabelCodes_h
#define cbc3d_LabelCodes_h

#include <cstdint>
#include <vector>

namespace cbc3d
{
/// Whether a label value fits the core's 32-bit labels.
inline bool FitsInt32(std::int64_t value)
{
  return value >= INT32_MIN && value <= INT32_MAX;
}

/// The table between the core's 32-bit labels ("codes") and the label values of an image or a
/// mesh, any 64-bit signed integers.
///
/// When every value fits in 32 bits there is no table: each code is its own value, so such
/// images mesh exactly as they always did. Otherwise code c stands for the c-th smallest
/// distinct value: codes compare like their values, so every order and tie-break of the core is
/// the same as it would be on the values themselves.
class LabelCodes
{
public:
  /// The codes for these values (any order, repeats allowed).
  static LabelCodes ForValues(std::vector<std::int64_t> values);

  /// True when codes are the values themselves (every value fits in 32 bits).
  bool IsIdentity() const { return this->Values.empty(); }

  /// The value a code stands for.
  std::int64_t ValueOf(std::int32_t code) const
  {
    return this->IsIdentity() ? code : this->Values[static_cast<std::size_t>(code)];
  }

  /// The code of `value`; false when it has none (a value the table was not built from, or
  /// one beyond 32 bits when there is no table).
  bool FindCode(std::int64_t value, std::int32_t& code) const;

private:
  std::vector<std::int64_t> Values; // ascending and distinct; empty: codes are values
};
} // namespace cbc3d

#endif
