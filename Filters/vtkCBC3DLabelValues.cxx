#include "vtkCBC3DLabelValues.h"

#include "cbc3d/base/Parallel.h"

#include <omp.h>

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

// The distinct labels one thread has seen, compacted (sorted, duplicates dropped) whenever
// they have doubled: label maps hold few, and a value is added only where it changes.
class DistinctLabels
{
public:
  void Add(std::int64_t label)
  {
    if (!this->Seen.empty() && this->Seen.back() == label)
    {
      return;
    }
    this->Seen.push_back(label);
    if (this->Seen.size() >= this->Limit)
    {
      this->Compact();
    }
  }
  void Compact()
  {
    std::sort(this->Seen.begin(), this->Seen.end());
    this->Seen.erase(std::unique(this->Seen.begin(), this->Seen.end()), this->Seen.end());
    this->Limit = std::max<std::size_t>(2 * this->Seen.size(), 4096);
  }
  std::vector<std::int64_t> Seen;

private:
  std::size_t Limit = 4096;
};

// One pass over the values as rows of RowLength (x fastest), on the threads: the distinct
// labels, the first value that is not a label (the one a message names, as a scan in order
// would find it) and, when Fill is set, each row's first and last value that is not Fill.
// The values are taken run by run (runs of one label are the rule), each run converted once.
struct Survey
{
  std::int64_t RowLength = 1;
  const std::int64_t* Fill = nullptr;
  int Threads = 1;
  std::vector<std::int64_t> Values; // ascending
  std::string Error;
  std::vector<std::array<int, 2>> Ends; // per row when Fill is set; { -1, -1 }: all Fill

  template <typename ArrayT>
  void operator()(ArrayT* array)
  {
    const auto range = vtk::DataArrayValueRange<1>(array);
    const std::int64_t count = static_cast<std::int64_t>(range.size());
    const std::int64_t rows = (count + this->RowLength - 1) / this->RowLength;
    if (this->Fill)
    {
      this->Ends.assign(static_cast<std::size_t>(rows), { -1, -1 });
    }
    const int threads = cbc3d::ThreadCount(this->Threads);
    std::vector<DistinctLabels> seen(static_cast<std::size_t>(threads));
    std::int64_t firstRefused = count;
    cbc3d::RegionErrors errors; // the lists of labels grow
#pragma omp parallel num_threads(threads) reduction(min : firstRefused)
    {
      DistinctLabels& mine = seen[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static)
      for (std::int64_t r = 0; r < rows; ++r)
      {
        const std::int64_t begin = r * this->RowLength;
        const std::int64_t end = std::min(count, begin + this->RowLength);
        errors.Run([&] { firstRefused = std::min(firstRefused, this->SurveyRow(range, begin, end, mine, r)); });
      }
    }
    errors.Rethrow();
    if (firstRefused < count)
    {
      this->Error = Refusal(range[firstRefused]);
      return;
    }
    for (DistinctLabels& labels : seen)
    {
      this->Values.insert(this->Values.end(), labels.Seen.begin(), labels.Seen.end());
    }
    std::sort(this->Values.begin(), this->Values.end());
    this->Values.erase(std::unique(this->Values.begin(), this->Values.end()), this->Values.end());
  }

  // Values begin..end-1, row r, run by run; returns the first that is not a label, or the
  // range's size.
  template <typename Range>
  std::int64_t SurveyRow(const Range& range, std::int64_t begin, std::int64_t end, DistinctLabels& seen, std::int64_t r)
  {
    std::int64_t firstRefused = static_cast<std::int64_t>(range.size());
    int first = -1, last = -1;
    for (std::int64_t i = begin; i < end;)
    {
      const auto value = range[i];
      const std::int64_t runStart = i;
      do
        ++i;
      while (i < end && range[i] == value); // a NaN is a run of one
      std::int64_t label = 0;
      if (!ToLabelValue(value, label))
      {
        firstRefused = std::min(firstRefused, runStart);
        continue;
      }
      seen.Add(label);
      if (!this->Fill || label != *this->Fill)
      {
        first = first < 0 ? int(runStart - begin) : first;
        last = int(i - 1 - begin);
      }
    }
    if (this->Fill)
    {
      this->Ends[static_cast<std::size_t>(r)] = { first, last };
    }
    return firstRefused;
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
// A value equal to the one before it takes its code without a search.
template <typename Range>
bool EncodeRange(const Range& range, const cbc3d::LabelCodes& codes, std::int32_t*& out)
{
  const auto end = range.end();
  auto it = range.begin();
  while (it != end)
  {
    const auto value = *it;
    std::int64_t label = 0;
    std::int32_t code = 0;
    if (!ToLabelValue(value, label) || !codes.FindCode(label, code))
    {
      return false;
    }
    for (; it != end && *it == value; ++it)
    {
      *out++ = code;
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

// Runs the survey over the array (of any type) and appends its values; false with its message.
bool RunSurvey(vtkDataArray* array, Survey& survey, std::vector<std::int64_t>& values, std::string& error)
{
  if (!vtkArrayDispatch::Dispatch::Execute(array, survey))
  {
    survey(array); // arrays the dispatcher does not know, through the generic API
  }
  error = survey.Error;
  values.insert(values.end(), survey.Values.begin(), survey.Values.end());
  return error.empty();
}
} // namespace

namespace vtkCBC3DLabelValues
{
bool CollectValues(vtkDataArray* array, std::vector<std::int64_t>& values, std::string& error, int threads)
{
  Survey survey;
  survey.RowLength = std::int64_t(1) << 16; // pieces for the threads
  survey.Threads = threads;
  return RunSurvey(array, survey, values, error);
}

bool CollectImageValues(vtkDataArray* array, const std::array<int, 3>& dimensions, std::int64_t fill,
  std::vector<std::int64_t>& values, std::string& error, std::array<int, 3>& lower, std::array<int, 3>& upper,
  int threads)
{
  Survey survey;
  survey.RowLength = std::max(dimensions[0], 1);
  survey.Fill = &fill;
  survey.Threads = threads;
  if (!RunSurvey(array, survey, values, error))
  {
    return false;
  }
  lower = dimensions;
  upper = { -1, -1, -1 };
  const int rowsPerSlice = std::max(dimensions[1], 1);
  for (std::size_t r = 0; r < survey.Ends.size(); ++r)
  {
    if (survey.Ends[r][0] < 0)
      continue;
    const int j = int(r % rowsPerSlice), k = int(r / rowsPerSlice);
    lower = { std::min(lower[0], survey.Ends[r][0]), std::min(lower[1], j), std::min(lower[2], k) };
    upper = { std::max(upper[0], survey.Ends[r][1]), std::max(upper[1], j), std::max(upper[2], k) };
  }
  return true;
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
