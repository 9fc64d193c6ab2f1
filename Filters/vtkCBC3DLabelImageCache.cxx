#include "vtkCBC3DLabelImageCache.h"

#include "vtkCBC3DConvert.h"

#include "cbc3d/base/LabelImage.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>

#include <algorithm>
#include <mutex>
#include <tuple>

namespace
{
// What a conversion depends on. Modification times only grow, so an array freed and another
// allocated at the same address never matches an old key.
struct Key
{
  const vtkDataArray* Labels = nullptr;
  vtkMTimeType LabelsTime = 0;
  const vtkImageData* Image = nullptr;
  vtkMTimeType ImageTime = 0;
  std::vector<vtkTypeInt64> BackgroundLabels;

  bool operator==(const Key& other) const
  {
    return std::tie(this->Labels, this->LabelsTime, this->Image, this->ImageTime, this->BackgroundLabels) ==
      std::tie(other.Labels, other.LabelsTime, other.Image, other.ImageTime, other.BackgroundLabels);
  }
};

std::mutex CacheMutex;
Key CachedKey;
std::shared_ptr<const cbc3d::LabelImage> Cached;

// Whether every value has a code in the image's table.
bool Codes(const cbc3d::LabelImage& image, const std::vector<std::int64_t>& values)
{
  std::int32_t code = 0;
  return std::all_of(values.begin(), values.end(),
    [&](std::int64_t value) { return image.Codes.FindCode(value, code); });
}
} // namespace

namespace vtkCBC3DLabelImageCache
{
std::shared_ptr<const cbc3d::LabelImage> Get(vtkImageData* image, vtkDataArray* labels,
  const std::vector<vtkTypeInt64>& backgroundLabels, const std::vector<std::int64_t>& otherValues,
  std::string& error, int threads)
{
  Key key;
  if (image && labels)
  {
    key = Key{ labels, labels->GetMTime(), image, image->GetMTime(), backgroundLabels };
    const std::lock_guard<std::mutex> lock(CacheMutex);
    if (Cached && key == CachedKey && Codes(*Cached, otherValues))
    {
      return Cached;
    }
    Cached.reset(); // stale: let it go before converting, so two images are not held at once
  }
  auto converted = std::make_shared<cbc3d::LabelImage>();
  if (!vtkCBC3DConvert::ToLabelImage(image, labels, backgroundLabels, *converted, error, otherValues, threads))
  {
    return nullptr;
  }
  const std::lock_guard<std::mutex> lock(CacheMutex);
  CachedKey = key;
  Cached = std::move(converted);
  return Cached;
}
} // namespace vtkCBC3DLabelImageCache
