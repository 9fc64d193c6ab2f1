#include "cbc3d/base/LabelCodes.h"

#include <algorithm>

namespace cbc3d
{
LabelCodes LabelCodes::ForValues(std::vector<std::int64_t> values)
{
  LabelCodes codes;
  if (std::all_of(values.begin(), values.end(), FitsInt32))
  {
    return codes;
  }
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  codes.Values = std::move(values);
  return codes;
}

bool LabelCodes::FindCode(std::int64_t value, std::int32_t& code) const
{
  if (this->IsIdentity())
  {
    code = static_cast<std::int32_t>(value);
    return FitsInt32(value);
  }
  const auto at = std::lower_bound(this->Values.begin(), this->Values.end(), value);
  if (at == this->Values.end() || *at != value)
  {
    return false;
  }
  code = static_cast<std::int32_t>(at - this->Values.begin());
  return true;
}
} // namespace cbc3d
