// libFuzzer target: vtkCBC3DNIfTIReader on arbitrary bytes, then the label-image conversion the
// filters and the cbc3d command apply to what it reads, then parts of the image. The bytes go through a temporary file
// (vtkNIFTIImageReader reads files only), named .nii.gz when they start with gzip's magic
// number so that the compressed path is fuzzed too. Errors are expected; crashes, leaks and
// undefined behaviour are not.
#include "vtkCBC3DConvert.h"
#include "vtkCBC3DNIfTIReader.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkObject.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

namespace
{
std::string TemporaryPath(const std::uint8_t* data, std::size_t size)
{
  const char* folder = std::getenv("TMPDIR");
  const bool gzip = size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
  return std::string(folder && *folder ? folder : "/tmp") + "/cbc3d-fuzz-nifti-" +
    std::to_string(getpid()) + (gzip ? ".nii.gz" : ".nii");
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  vtkObject::GlobalWarningDisplayOff(); // every rejected input would print its error
  const std::string path = TemporaryPath(data, size);
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  vtkNew<vtkCBC3DNIfTIReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (image->GetNumberOfPoints() > 0)
  {
    cbc3d::LabelImage labels;
    std::string error;
    vtkCBC3DConvert::ToLabelImage(
      image, vtkCBC3DConvert::ChooseLabelArray(nullptr, image), { 0 }, labels, error);
    // Parts too, as a parallel pipeline asks them (a .nii.gz's are streamed): the upper half
    // slab, then a box cropped in x as well.
    int part[6];
    image->GetExtent(part);
    part[4] = (part[4] + part[5] + 1) / 2;
    reader->UpdateExtent(part);
    part[0] = (part[0] + part[1] + 1) / 2;
    reader->UpdateExtent(part);
  }
  std::remove(path.c_str());
  return 0;
}
