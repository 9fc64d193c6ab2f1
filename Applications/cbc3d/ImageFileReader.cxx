#include "ImageFileReader.h"

#include "CommandLine.h"
#include "ErrorCapture.h"

#include "vtkCBC3DNIfTIReader.h"

#include <vtkAlgorithm.h>
#include <vtkMetaImageReader.h>
#include <vtkNew.h>
#include <vtkNrrdReader.h>
#include <vtkXMLImageDataReader.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sys/stat.h>

namespace
{
template <typename ReaderT>
vtkSmartPointer<vtkAlgorithm> MakeReader(const std::string& path)
{
  auto reader = vtkSmartPointer<ReaderT>::New();
  reader->SetFileName(path.c_str());
  return reader;
}
} // namespace

vtkSmartPointer<vtkImageData> ReadImageFile(const std::string& path, std::string& error)
{
  struct stat info;
  if (stat(path.c_str(), &info) != 0)
  {
    error = "cannot read '" + path + "': " + std::strerror(errno);
    return nullptr;
  }
  if (S_ISDIR(info.st_mode))
  {
    error = "cannot read '" + path + "': it is a directory";
    return nullptr;
  }
  if (!std::ifstream(path).good())
  {
    error = "cannot read '" + path + "': " + std::strerror(errno);
    return nullptr;
  }

  const std::string extension = FileExtension(path);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (extension == ".nii" || extension == ".nii.gz")
  {
    reader = MakeReader<vtkCBC3DNIfTIReader>(path);
  }
  else if (extension == ".nrrd" || extension == ".nhdr")
  {
    reader = MakeReader<vtkNrrdReader>(path);
  }
  else if (extension == ".mha" || extension == ".mhd")
  {
    reader = MakeReader<vtkMetaImageReader>(path);
  }
  else if (extension == ".vti")
  {
    reader = MakeReader<vtkXMLImageDataReader>(path);
  }
  else
  {
    error = "unknown image extension '" + extension + "' for '" + path +
      "': use .nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd or .vti";
    return nullptr;
  }

  vtkNew<ErrorCapture> capture;
  capture->Observe(reader);
  reader->Update();
  vtkImageData* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!capture->Error.empty() || !image || image->GetNumberOfPoints() == 0)
  {
    error = "cannot read '" + path + "' as a " + extension.substr(1) + " image" +
      (capture->Error.empty() ? std::string() : ": " + capture->Error);
    return nullptr;
  }
  vtkSmartPointer<vtkImageData> result = vtkSmartPointer<vtkImageData>::New();
  result->ShallowCopy(image);
  return result;
}
