#include "vtkCBC3DNIfTIGzipVoxels.h"

#include <vtkByteSwap.h>
#include <vtk_zlib.h>
#include <vtksys/SystemTools.hxx>

#include <libdeflate.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <vector>

namespace
{
constexpr std::size_t NIfTI1HeaderBytes = 348;

bool ReadWholeFile(const std::string& fileName, std::vector<unsigned char>& bytes)
{
  std::ifstream file(fileName, std::ios::binary | std::ios::ate);
  if (!file)
    return false;
  const std::streamoff size = file.tellg();
  if (size <= 0)
    return false;
  bytes.resize(static_cast<std::size_t>(size));
  file.seekg(0);
  return static_cast<bool>(file.read(reinterpret_cast<char*>(bytes.data()), size));
}

// Inflates every gzip member of `in` into `out` (exactly `size` bytes): false where the stream
// is corrupt, shorter, or holds more than that.
bool InflateAll(const std::vector<unsigned char>& in, unsigned char* out, std::size_t size)
{
  std::unique_ptr<libdeflate_decompressor, void (*)(libdeflate_decompressor*)> inflater(
    libdeflate_alloc_decompressor(), libdeflate_free_decompressor);
  if (!inflater)
    return false;
  std::size_t read = 0, written = 0;
  while (read < in.size() && written < size)
  {
    std::size_t used = 0, made = 0;
    if (libdeflate_gzip_decompress_ex(inflater.get(), in.data() + read, in.size() - read, out + written,
          size - written, &used, &made) != LIBDEFLATE_SUCCESS)
      return false;
    read += used;
    written += made;
  }
  return written == size && read == in.size();
}

template <typename T>
T HeaderField(const unsigned char* header, std::size_t offset, bool swap)
{
  T value;
  std::memcpy(&value, header + offset, sizeof(T));
  if (swap)
    vtkByteSwap::SwapVoidRange(&value, 1, sizeof(T));
  return value;
}
} // namespace

vtkSmartPointer<vtkDataArray> InflateNIfTIVoxels(const std::string& fileName, int scalarType, vtkIdType voxels)
{
  std::vector<unsigned char> compressed;
  if (!vtksys::SystemTools::StringEndsWith(fileName, ".nii.gz") || voxels <= 0 || !ReadWholeFile(fileName, compressed))
    return nullptr;
  vtkSmartPointer<vtkDataArray> array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(scalarType));
  if (!array)
    return nullptr;
  const std::size_t valueBytes = static_cast<std::size_t>(array->GetDataTypeSize());
  // The header first (zlib streams it: a few hundred bytes), to learn where the voxels start.
  unsigned char header[NIfTI1HeaderBytes];
  gzFile file = gzopen(fileName.c_str(), "rb");
  if (!file)
    return nullptr;
  const int headerBytes = gzread(file, header, sizeof(header));
  gzclose(file);
  if (headerBytes != int(sizeof(header)))
    return nullptr;
  const bool swap = HeaderField<std::int32_t>(header, 0, false) != std::int32_t(NIfTI1HeaderBytes);
  if (HeaderField<std::int32_t>(header, 0, swap) != std::int32_t(NIfTI1HeaderBytes) ||
    std::memcmp(header + 344, "n+1", 4) != 0)
    return nullptr;
  const std::int16_t dimensions = HeaderField<std::int16_t>(header, 40, swap);
  for (int d = 4; d <= 7 && d <= dimensions; ++d)
    if (HeaderField<std::int16_t>(header, 40 + 2 * d, swap) > 1)
      return nullptr; // several volumes, or values of several components
  const float qfac = HeaderField<float>(header, 76, swap);
  const float voxelOffset = HeaderField<float>(header, 108, swap);
  if (qfac < 0 || !(voxelOffset >= NIfTI1HeaderBytes) || voxelOffset > 1e9f || voxelOffset != float(std::size_t(voxelOffset)))
    return nullptr;
  const std::size_t offset = static_cast<std::size_t>(voxelOffset);
  const std::size_t dataBytes = valueBytes * static_cast<std::size_t>(voxels);
  // Deflate expands at most 1032 times: a header claiming more is corrupt (and would only make
  // this allocate it).
  if (double(offset + dataBytes) > 1032.0 * double(compressed.size()))
    return nullptr;
  auto* block = static_cast<unsigned char*>(std::malloc(offset + dataBytes));
  if (!block)
    return nullptr;
  if (!InflateAll(compressed, block, offset + dataBytes))
  {
    std::free(block);
    return nullptr;
  }
  std::memmove(block, block + offset, dataBytes);
  if (swap && valueBytes > 1)
    vtkByteSwap::SwapVoidRange(block, voxels, static_cast<int>(valueBytes));
  array->SetVoidArray(block, voxels, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  return array;
}
