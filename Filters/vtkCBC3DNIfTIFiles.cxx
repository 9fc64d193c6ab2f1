#include "vtkCBC3DNIfTIFiles.h"

#include <vtkMatrix4x4.h>

#include <vtk_zlib.h>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

// Largest deviation of a matrix's 3x3 part M from orthonormality: max |M^T M - I|.
double vtkCBC3DNIfTIFiles::OrthonormalityError(vtkMatrix4x4* m)
{
  double error = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    for (int b = 0; b < 3; ++b)
    {
      double dot = 0.0;
      for (int r = 0; r < 3; ++r)
      {
        dot += m->GetElement(r, a) * m->GetElement(r, b);
      }
      error = std::max(error, std::fabs(dot - (a == b ? 1.0 : 0.0)));
    }
  }
  return error;
}

// The file that holds the voxels: the .img (.img.gz) beside an Analyze/NIfTI .hdr, otherwise
// the file itself. Empty when a .hdr has no such file (the inner reader then says so).
std::string vtkCBC3DNIfTIFiles::VoxelFileName(const std::string& fileName)
{
  const std::string lower = vtksys::SystemTools::LowerCase(fileName);
  for (const char* header : { ".hdr", ".hdr.gz" })
  {
    if (vtksys::SystemTools::StringEndsWith(lower, header))
    {
      const std::string stem = fileName.substr(0, fileName.size() - std::string(header).size());
      for (const char* data : { ".img", ".img.gz" })
      {
        if (vtksys::SystemTools::FileExists(stem + data, true))
        {
          return stem + data;
        }
      }
      return std::string();
    }
  }
  return fileName;
}

// The datatype codes the NIfTI-1 and -2 standards define. vtkNIFTIImageReader reads some of
// them and refuses the others with an error, but other values can crash it (found by the NIfTI
// fuzzer: datatype 25973 made its RequestInformation read out of bounds), so any other value is
// refused before it reads the header.
constexpr std::array<int, 17> NIfTIDataTypes = { 1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 768, 1024,
  1280, 1536, 1792, 2048, 2304 };
// The ones a label map can be: integers and reals of one component. Bits, complex, RGB and
// 128-bit floats are refused before VTK's reader sees them (a complex256 header made it ask for
// a vector of negative length: found by the NIfTI fuzzer).
constexpr std::array<int, 10> LabelDataTypes = { 2, 4, 8, 16, 64, 256, 512, 768, 1024, 1280 };

// The header file of a .hdr/.img pair given by its .img, otherwise the file itself.
std::string vtkCBC3DNIfTIFiles::HeaderFileName(const std::string& fileName)
{
  const std::string lower = vtksys::SystemTools::LowerCase(fileName);
  for (const char* image : { ".img", ".img.gz" })
  {
    if (vtksys::SystemTools::StringEndsWith(lower, image))
    {
      const std::string stem = fileName.substr(0, fileName.size() - std::string(image).size());
      for (const char* header : { ".hdr", ".hdr.gz" })
      {
        if (vtksys::SystemTools::FileExists(stem + header, true))
        {
          return stem + header;
        }
      }
    }
  }
  return fileName;
}

// What is wrong with the header's sizeof_hdr or datatype fields, in words; empty when both are
// sound or the file is too short to tell (vtkNIFTIImageReader then says why it cannot read it).
// sizeof_hdr must be 348 (NIfTI-1, Analyze 7.5; datatype at byte 70) or 540 (NIfTI-2; at byte
// 12), in either byte order: it is how readers tell the byte order, and VTK's reader read a
// header whose sizeof_hdr was 0 and crashed on its datatype.
std::string vtkCBC3DNIfTIFiles::HeaderProblem(const std::string& headerFile)
{
  unsigned char header[540];
  gzFile file = gzopen(headerFile.c_str(), "rb");
  if (!file)
  {
    return std::string();
  }
  const int length = gzread(file, header, sizeof(header));
  gzclose(file);
  if (length < 4)
  {
    return std::string();
  }
  auto field = [&](int offset, int bytes, bool swap) {
    std::uint32_t value = 0;
    for (int b = 0; b < bytes; ++b)
    {
      value |= std::uint32_t(header[offset + (swap ? bytes - 1 - b : b)]) << (8 * b);
    }
    return value;
  };
  for (const bool sizeSwap : { false, true })
  {
    const std::uint32_t size = field(0, 4, sizeSwap);
    const int offset = size == 348 ? 70 : size == 540 ? 12 : -1;
    if (offset < 0)
    {
      continue;
    }
    const int dimOffset = size == 348 ? 40 : 16; // dim[0]: int16 in NIfTI-1, int64 (low bytes) in -2
    if (length < offset + 2 || length < dimOffset + 8)
    {
      return std::string();
    }
    // VTK's reader takes the byte order in which dim[0] is 1 to 7, whatever sizeof_hdr says (an
    // input with sizeof_hdr 348 and a dim[0] valid only swapped crashed it on the swapped
    // datatype): the datatype is checked in that order.
    auto dimAt = [&](int i, bool swap) {
      return size == 348 ? int(static_cast<std::int16_t>(field(dimOffset + 2 * i, 2, swap)))
                         : int(field(dimOffset + 8 * i + (swap ? 4 : 0), 4, swap));
    };
    auto dim0 = [&](bool swap) { return dimAt(0, swap); };
    const bool swap = (dim0(sizeSwap) >= 1 && dim0(sizeSwap) <= 7) ? sizeSwap : !sizeSwap;
    if (dim0(swap) < 1 || dim0(swap) > 7)
    {
      return "its dim[0] is " + std::to_string(dim0(sizeSwap)) + ", not 1 to 7 in either byte order";
    }
    // Every axis the header declares needs a voxel: dim[5] = 0 (no vector components) beside
    // dim[0] = 7 made VTK's reader divide by zero (found by the NIfTI fuzzer).
    if (length >= dimOffset + (size == 348 ? 16 : 64))
    {
      for (int i = 1; i <= dim0(swap); ++i)
      {
        if (dimAt(i, swap) < 1)
        {
          return "its dim[" + std::to_string(i) + "] is " + std::to_string(dimAt(i, swap)) +
            ": no voxels along an axis";
        }
      }
    }
    const int dataType = static_cast<std::int16_t>(field(offset, 2, swap));
    if (std::find(NIfTIDataTypes.begin(), NIfTIDataTypes.end(), dataType) == NIfTIDataTypes.end())
    {
      return "its datatype " + std::to_string(dataType) + " is not a NIfTI data type";
    }
    if (std::find(LabelDataTypes.begin(), LabelDataTypes.end(), dataType) == LabelDataTypes.end())
    {
      return "its datatype " + std::to_string(dataType) +
        " is not a label type: a label map holds integers or reals, not bits or values of several components (complex numbers, colours)";
    }
    return std::string();
  }
  return "its sizeof_hdr is " + std::to_string(static_cast<std::int32_t>(field(0, 4, false))) +
    ", neither 348 (NIfTI-1, Analyze 7.5) nor 540 (NIfTI-2)";
}
