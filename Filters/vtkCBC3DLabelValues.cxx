#include "vtkCBC3DLabelValues.h"

#include "cbc3d/Parallel.h"

#include <vtkArrayDispatch.h>
#include <vtkDataArrayRange.h>
#include <vtkIntArray.h>
#include <vtkLongArray.h>
#include <vtkTypeInt64Array.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <type_traits>

namespace
{
// The exact 64-bit signed value of a label of any arithmetic type; false when there is none.
template <typename T>
bool ToLabelValue(T value, std::int64_t& out)
{
  if constexpr (std::is_floating_point_v<T>)
  {
    constexpr double limit = 9223372036854775808.0; // 2^63
    if (!(value >= -limit && value < limit) || value != std::floor(value))
    {
      return false;
    }
  }
  else if constexpr (std::is_unsigned_v<T> && sizeof(T) >= sizeof(std::int64_t))
  {
    if (value > static_cast<T>(std::numeric_limits<std::int64_t>::max()))
    {
      return false;
    }
  }
  out = static_cast<std::int64_t>(value);
  return true;
}

template <typename T>
std::string Refusal(T value)
{
  std::ostringstream msg;
  msg.precision(17);
  if (std::is_floating_point_v<T> && std::isfinite(static_cast<double>(value)) &&
    static_cast<double>(value) != std::floor(static_cast<double>(value)))
  {
    msg << "the label array holds the non-integral value " << +value
        << "; a label map needs whole-number labels";
  }
  else
  {
    msg << "the label array holds " << +value
        << ", which is not a label: labels are integers from -9223372036854775808 to "
           "9223372036854775807";
  }
  return msg.str();
}

// The array for labels beyond 32 bits: a 64-bit vtkLongArray where long has 64 bits (Debian),
// since the legacy .vtk writer names it "long", which meshio reads, and vtkTypeInt64Array
// "vtktypeint64", which meshio 5.0's legacy reader refuses.
using LargeLabelArray = std::conditional_t<VTK_SIZEOF_LONG == 8, vtkLongArray, vtkTypeInt64Array>;

// Labels usually span a short range: a table of the values present beats sorting every voxel.
constexpr std::int64_t LongestPresenceTable = std::int64_t(1) << 24;

// Checks every value and gathers the distinct ones: through a table of the values present when
// they span a short range (the usual case, and no copy of the image), else by sorting a copy.
struct Collect
{
  std::vector<std::int64_t>* Values = nullptr;
  std::string Error;
  int Threads = 1;

  template <typename ArrayT>
  void operator()(ArrayT* array)
  {
    const auto range = vtk::DataArrayValueRange<1>(array);
    const std::int64_t count = static_cast<std::int64_t>(range.size());
    if (count == 0)
    {
      return;
    }
    // The range, and the first value that is not a label (the one the message names, as a
    // scan in order would find it), on the threads.
    std::int64_t lowest = std::numeric_limits<std::int64_t>::max();
    std::int64_t highest = std::numeric_limits<std::int64_t>::min();
    std::int64_t firstRefused = count;
#pragma omp parallel for schedule(static) num_threads(cbc3d::ThreadCount(this->Threads)) \
  reduction(min : lowest, firstRefused) reduction(max : highest)
    for (std::int64_t i = 0; i < count; ++i)
    {
      std::int64_t label = 0;
      if (!ToLabelValue(range[i], label))
      {
        firstRefused = std::min(firstRefused, i);
        continue;
      }
      lowest = std::min(lowest, label);
      highest = std::max(highest, label);
    }
    if (firstRefused < count)
    {
      this->Error = Refusal(range[firstRefused]);
      return;
    }
    if (highest / 2 - lowest / 2 < LongestPresenceTable / 2)
    {
      this->AddPresent(range, lowest, highest);
      return;
    }
    std::vector<std::int64_t> all;
    all.reserve(range.size());
    std::int64_t label = 0;
    for (const auto value : range)
    {
      ToLabelValue(value, label);
      all.push_back(label);
    }
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    this->Values->insert(this->Values->end(), all.begin(), all.end());
  }

  // Appends the values present, in ascending order, through one table of the range per thread.
  template <typename Range>
  void AddPresent(const Range& range, std::int64_t lowest, std::int64_t highest)
  {
    const std::size_t span = static_cast<std::size_t>(highest - lowest + 1);
    const std::int64_t count = static_cast<std::int64_t>(range.size());
    std::vector<char> present(span, 0);
#pragma omp parallel num_threads(cbc3d::ThreadCount(this->Threads))
    {
      std::vector<char> mine(span, 0);
      std::int64_t label = 0;
#pragma omp for schedule(static) nowait
      for (std::int64_t i = 0; i < count; ++i)
      {
        ToLabelValue(range[i], label);
        mine[static_cast<std::size_t>(label - lowest)] = 1;
      }
#pragma omp critical
      for (std::size_t offset = 0; offset < span; ++offset)
        present[offset] |= mine[offset];
    }
    for (std::size_t offset = 0; offset < span; ++offset)
      if (present[offset])
        this->Values->push_back(lowest + static_cast<std::int64_t>(offset));
  }
};

// The rows of a box of the image, x fastest: the value range of each, on `Threads` threads
// (`visit` must be safe to call from several at once; it says whether to go on).
struct BoxRows
{
  std::array<int, 3> Dimensions, Lower, Size;
  int Threads = 1;

  template <typename ArrayT, typename Visit>
  void ForEach(ArrayT* array, Visit visit) const
  {
    const std::int64_t rows = std::int64_t(this->Size[1]) * this->Size[2];
    bool going = true;
#pragma omp parallel for schedule(static) num_threads(cbc3d::ThreadCount(this->Threads))
    for (std::int64_t r = 0; r < rows; ++r)
    {
      bool goOn;
#pragma omp atomic read
      goOn = going;
      if (!goOn)
        continue;
      const int j = this->Lower[1] + int(r % this->Size[1]);
      const int k = this->Lower[2] + int(r / this->Size[1]);
      const vtkIdType start =
        this->Lower[0] + vtkIdType(this->Dimensions[0]) * (j + vtkIdType(this->Dimensions[1]) * k);
      if (!visit(vtk::DataArrayValueRange<1>(array, start, start + this->Size[0]), r, j, k))
      {
#pragma omp atomic write
        going = false;
      }
    }
  }
};

// Writes the codes of the values of `range` from `out` on; false for a value the codes lack.
template <typename Range>
bool EncodeRange(const Range& range, const cbc3d::LabelCodes& codes, std::int32_t*& out)
{
  for (const auto value : range)
  {
    std::int64_t label = 0;
    if (!ToLabelValue(value, label) || !codes.FindCode(label, *out++))
    {
      return false;
    }
  }
  return true;
}

// The whole array, or only a box of it when Box is set.
struct Encode
{
  const cbc3d::LabelCodes* Codes = nullptr;
  std::int32_t* Out = nullptr;
  const BoxRows* Box = nullptr;
  bool Ok = true;

  template <typename ArrayT>
  void operator()(ArrayT* array)
  {
    if (!this->Box)
    {
      std::int32_t* out = this->Out;
      this->Ok = EncodeRange(vtk::DataArrayValueRange<1>(array), *this->Codes, out);
      return;
    }
    bool ok = true;
    this->Box->ForEach(array, [&](const auto& row, std::int64_t r, int, int) {
      std::int32_t* out = this->Out + r * this->Box->Size[0];
      if (EncodeRange(row, *this->Codes, out))
        return true;
#pragma omp atomic write
      ok = false;
      return false;
    });
    this->Ok = ok;
  }
};

struct FindBox
{
  BoxRows Whole;
  std::int64_t Fill = 0;
  std::array<int, 3> Lower, Upper;

  template <typename ArrayT>
  void operator()(ArrayT* array)
  {
    // Each row's first and last voxel that is not Fill, gathered per row and then combined:
    // min and max in any order are the same.
    const std::int64_t rows = std::int64_t(this->Whole.Size[1]) * this->Whole.Size[2];
    std::vector<std::array<int, 2>> ends(rows, { -1, -1 });
    this->Whole.ForEach(array, [&](const auto& row, std::int64_t r, int, int) {
      auto isFill = [&](auto value) {
        std::int64_t label = 0;
        return ToLabelValue(value, label) && label == this->Fill;
      };
      const auto first = std::find_if_not(row.begin(), row.end(), isFill);
      if (first == row.end())
        return true;
      auto end = row.end();
      do
        --end;
      while (isFill(*end));
      ends[r] = { int(first - row.begin()), int(end - row.begin()) };
      return true;
    });
    this->Lower = this->Whole.Dimensions;
    this->Upper = { -1, -1, -1 };
    for (std::int64_t r = 0; r < rows; ++r)
    {
      if (ends[r][0] < 0)
        continue;
      const int j = int(r % this->Whole.Size[1]), k = int(r / this->Whole.Size[1]);
      this->Lower = { std::min(this->Lower[0], ends[r][0]), std::min(this->Lower[1], j), std::min(this->Lower[2], k) };
      this->Upper = { std::max(this->Upper[0], ends[r][1]), std::max(this->Upper[1], j), std::max(this->Upper[2], k) };
    }
  }
};
} // namespace

namespace vtkCBC3DLabelValues
{
bool CollectValues(vtkDataArray* array, std::vector<std::int64_t>& values, std::string& error, int threads)
{
  Collect collect;
  collect.Values = &values;
  collect.Threads = threads;
  if (!vtkArrayDispatch::Dispatch::Execute(array, collect))
  {
    collect(array); // arrays the dispatcher does not know, through the generic API
  }
  error = collect.Error;
  return error.empty();
}

bool ToCodes(vtkDataArray* array, const cbc3d::LabelCodes& codes, std::int32_t* out)
{
  Encode encode;
  encode.Codes = &codes;
  encode.Out = out;
  if (!vtkArrayDispatch::Dispatch::Execute(array, encode))
  {
    encode(array);
  }
  return encode.Ok;
}

bool ToCodes(vtkDataArray* array, const cbc3d::LabelCodes& codes, const std::array<int, 3>& dimensions,
  const std::array<int, 3>& lower, const std::array<int, 3>& size, std::int32_t* out, int threads)
{
  Encode encode;
  encode.Codes = &codes;
  encode.Out = out;
  const BoxRows box{ dimensions, lower, size, threads };
  encode.Box = &box;
  if (!vtkArrayDispatch::Dispatch::Execute(array, encode))
  {
    encode(array);
  }
  return encode.Ok;
}

bool OtherValuesBox(vtkDataArray* array, const std::array<int, 3>& dimensions, std::int64_t fill,
  std::array<int, 3>& lower, std::array<int, 3>& upper, int threads)
{
  FindBox find;
  find.Whole = BoxRows{ dimensions, { 0, 0, 0 }, dimensions, threads };
  find.Fill = fill;
  if (!vtkArrayDispatch::Dispatch::Execute(array, find))
  {
    find(array);
  }
  if (find.Upper[0] < 0)
  {
    return false; // lower and upper as they were
  }
  lower = find.Lower;
  upper = find.Upper;
  return true;
}

vtkSmartPointer<vtkDataArray> FromCodes(const std::vector<std::int32_t>& labels,
  const cbc3d::LabelCodes& codes, const char* name, int components)
{
  const bool fits = std::all_of(labels.begin(), labels.end(),
    [&](std::int32_t code) { return cbc3d::FitsInt32(codes.ValueOf(code)); });
  vtkSmartPointer<vtkDataArray> array;
  if (fits)
  {
    array = vtkSmartPointer<vtkIntArray>::New();
  }
  else
  {
    array = vtkSmartPointer<LargeLabelArray>::New();
  }
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(labels.size()) / components);
  if (auto* ints = vtkIntArray::SafeDownCast(array))
  {
    for (std::size_t i = 0; i < labels.size(); ++i)
      ints->SetValue(static_cast<vtkIdType>(i), static_cast<int>(codes.ValueOf(labels[i])));
  }
  else
  {
    auto* longs = LargeLabelArray::SafeDownCast(array);
    for (std::size_t i = 0; i < labels.size(); ++i)
      longs->SetValue(static_cast<vtkIdType>(i), codes.ValueOf(labels[i]));
  }
  return array;
}
} // namespace vtkCBC3DLabelValues
