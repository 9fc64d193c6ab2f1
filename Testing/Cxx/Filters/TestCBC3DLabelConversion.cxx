// The conversion of a label array into the core's label image reads the image on several
// threads (the values present, the box that is not background, the codes): the result, and the
// message for a value that is not a label, are the same for any number of threads.
#include "vtkCBC3DConvert.h"

#include "cbc3d/base/LabelImage.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <iostream>
#include <random>
#include <string>

namespace
{
// A 37 x 29 x 23 float image, background 0 around a box of labels -3, 7 and 1000000 (a
// presence table over a wide range) from a fixed random sequence.
vtkSmartPointer<vtkImageData> RandomLabels()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(37, 29, 23);
  vtkNew<vtkFloatArray> labels;
  labels->SetName("labels");
  labels->SetNumberOfTuples(37 * 29 * 23);
  std::mt19937 random(3);
  const float values[] = { -3.0f, 7.0f, 1000000.0f, 0.0f };
  for (int k = 0; k < 23; ++k)
    for (int j = 0; j < 29; ++j)
      for (int i = 0; i < 37; ++i)
      {
        const bool box = i >= 5 && i < 30 && j >= 3 && j < 20 && k >= 8 && k < 21;
        labels->SetValue(i + 37 * (j + 29 * k), box ? values[random() % 4] : 0.0f);
      }
  image->GetPointData()->SetScalars(labels);
  return image;
}

bool Same(const cbc3d::LabelImage& a, const cbc3d::LabelImage& b)
{
  if (a.Labels != b.Labels || a.StoredLower != b.StoredLower || a.StoredSize != b.StoredSize ||
    a.BackgroundLabels != b.BackgroundLabels)
    return false;
  for (const std::int32_t code : a.Labels)
    if (a.Codes.ValueOf(code) != b.Codes.ValueOf(code))
      return false;
  return true;
}
} // namespace

int TestCBC3DLabelConversion(int, char*[])
{
  vtkSmartPointer<vtkImageData> image = RandomLabels();
  vtkDataArray* labels = image->GetPointData()->GetScalars();
  cbc3d::LabelImage serial;
  std::string error;
  if (!vtkCBC3DConvert::ToLabelImage(image, labels, { 0 }, serial, error, {}, 1))
  {
    std::cerr << "conversion failed: " << error << "\n";
    return 1;
  }
  // The box of the labels and one voxel around it.
  if (serial.StoredLower != std::array<int, 3>{ 4, 2, 7 } || serial.StoredSize != std::array<int, 3>{ 27, 19, 15 })
  {
    std::cerr << "stored box " << serial.StoredLower[0] << "," << serial.StoredLower[1] << ","
              << serial.StoredLower[2] << " size " << serial.StoredSize[0] << "," << serial.StoredSize[1]
              << "," << serial.StoredSize[2] << "\n";
    return 1;
  }
  // Every stored voxel holds its value in the array (runs of one value share one lookup).
  for (int k = 0; k < serial.StoredSize[2]; ++k)
    for (int j = 0; j < serial.StoredSize[1]; ++j)
      for (int i = 0; i < serial.StoredSize[0]; ++i)
      {
        const std::int32_t code = serial.Labels[i + serial.StoredSize[0] * (j + std::size_t(serial.StoredSize[1]) * k)];
        const int x = i + serial.StoredLower[0], y = j + serial.StoredLower[1], z = k + serial.StoredLower[2];
        if (serial.Codes.ValueOf(code) != static_cast<std::int64_t>(labels->GetComponent(x + 37 * (y + 29 * z), 0)))
        {
          std::cerr << "voxel " << x << "," << y << "," << z << " holds " << serial.Codes.ValueOf(code) << "\n";
          return 1;
        }
      }
  for (const int threads : { 2, 3, 0 })
  {
    cbc3d::LabelImage parallel;
    if (!vtkCBC3DConvert::ToLabelImage(image, labels, { 0 }, parallel, error, {}, threads) ||
      !Same(serial, parallel))
    {
      std::cerr << threads << " threads: not the serial conversion " << error << "\n";
      return 1;
    }
  }
  // Two values that are not labels: the message names the first in the array's order.
  static_cast<vtkFloatArray*>(labels)->SetValue(37 * 29 * 12 + 40, 2.5f);
  static_cast<vtkFloatArray*>(labels)->SetValue(37 * 29 * 20 + 3, 4.25f);
  for (const int threads : { 1, 3 })
  {
    cbc3d::LabelImage refused;
    error.clear();
    if (vtkCBC3DConvert::ToLabelImage(image, labels, { 0 }, refused, error, {}, threads) ||
      error != "the label array holds the non-integral value 2.5; a label map needs whole-number labels")
    {
      std::cerr << threads << " threads: '" << error << "'\n";
      return 1;
    }
  }
  return 0;
}
