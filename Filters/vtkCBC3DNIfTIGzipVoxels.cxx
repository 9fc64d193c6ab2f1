#include "vtkCBC3DNIfTIGzipVoxels.h"

#include <vtkByteSwap.h>
#include <vtk_zlib.h>
#include <vtksys/SystemTools.hxx>

#include <libdeflate.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <vector>

namespace
{
constexpr std::size_t NIfTI1HeaderBytes = 348;
// gzread counts in unsigned int and answers in int: longer reads go in pieces of 1 GiB.
constexpr std::size_t LargestRead = std::size_t(1) << 30;
// Bytes before and between the asked slices are inflated into (and dropped from) a buffer of
// at most this size, so skipping costs no memory of the image's size.
constexpr std::size_t SkipBufferBytes = std::size_t(1) << 20;

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

// Where the voxels start in the inflated file and whether their bytes need swapping; false for
// a file this path does not read.
bool ReadVoxelLayout(const std::string& fileName, std::size_t& offset, bool& swap)
{
  // zlib streams the header: a few hundred bytes.
  unsigned char header[NIfTI1HeaderBytes];
  gzFile file = gzopen(fileName.c_str(), "rb");
  if (!file)
    return false;
  const int headerBytes = gzread(file, header, sizeof(header));
  gzclose(file);
  if (headerBytes != int(sizeof(header)))
    return false;
  swap = HeaderField<std::int32_t>(header, 0, false) != std::int32_t(NIfTI1HeaderBytes);
  if (HeaderField<std::int32_t>(header, 0, swap) != std::int32_t(NIfTI1HeaderBytes) ||
    std::memcmp(header + 344, "n+1", 4) != 0)
    return false;
  const std::int16_t dimensions = HeaderField<std::int16_t>(header, 40, swap);
  for (int d = 4; d <= 7 && d <= dimensions; ++d)
    if (HeaderField<std::int16_t>(header, 40 + 2 * d, swap) > 1)
      return false; // several volumes, or values of several components
  const float qfac = HeaderField<float>(header, 76, swap);
  const float voxelOffset = HeaderField<float>(header, 108, swap);
  if (qfac < 0 || !(voxelOffset >= NIfTI1HeaderBytes) || voxelOffset > 1e9f || voxelOffset != float(std::size_t(voxelOffset)))
    return false;
  offset = static_cast<std::size_t>(voxelOffset);
  return true;
}

// The whole voxel block, inflated at once into a malloc'd block; null on failure.
unsigned char* InflateWhole(const std::string& fileName, std::size_t offset, std::size_t dataBytes)
{
  std::vector<unsigned char> compressed;
  if (!ReadWholeFile(fileName, compressed))
    return nullptr;
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
  return block;
}

// zlib's stream of the file, read forward: exact reads, and skips through a small buffer.
class GzipStream
{
public:
  explicit GzipStream(const std::string& fileName)
    : File(gzopen(fileName.c_str(), "rb"))
  {
    if (this->File)
      gzbuffer(this->File, 1 << 17); // fewer, larger reads of the compressed file
  }
  ~GzipStream()
  {
    if (this->File)
      gzclose(this->File);
  }
  GzipStream(const GzipStream&) = delete;
  GzipStream& operator=(const GzipStream&) = delete;

  bool Read(unsigned char* out, std::size_t bytes)
  {
    while (this->File && bytes > 0)
    {
      const unsigned piece = static_cast<unsigned>(std::min(bytes, LargestRead));
      if (gzread(this->File, out, piece) != int(piece))
        return false; // corrupt, or shorter than the header says
      out += piece;
      bytes -= piece;
    }
    return this->File != nullptr;
  }

  bool Skip(std::size_t bytes)
  {
    if (bytes > 0 && this->Scratch.empty())
      this->Scratch.resize(std::min(bytes, SkipBufferBytes));
    while (bytes > 0)
    {
      const std::size_t piece = std::min(bytes, this->Scratch.size());
      if (!this->Read(this->Scratch.data(), piece))
        return false;
      bytes -= piece;
    }
    return this->File != nullptr;
  }

private:
  gzFile File;
  std::vector<unsigned char> Scratch;
};

// The voxels of `box` (indices from 0 in an image of `dims` voxels) into `out`, inflating the
// stream up to the box's last slice and keeping only the box's bytes.
bool InflateBox(const std::string& fileName, std::size_t offset, std::size_t valueBytes,
  const int dims[3], const int box[6], unsigned char* out)
{
  GzipStream stream(fileName);
  const std::size_t row = valueBytes * dims[0], slice = row * dims[1];
  const std::size_t boxRow = valueBytes * (box[1] - box[0] + 1);
  const std::size_t rows = box[3] - box[2] + 1, slices = box[5] - box[4] + 1;
  if (!stream.Skip(offset + slice * box[4]))
    return false;
  if (boxRow == row && rows == std::size_t(dims[1]))
    return stream.Read(out, slice * slices); // a slab: the slices straight into the output
  // A general box: each slice's rows from box[2] to box[3], cropped in x where x is cropped.
  std::vector<unsigned char> rowBuffer(boxRow == row ? 0 : row * rows);
  for (std::size_t k = 0; k < slices; ++k)
  {
    if (!stream.Skip(row * box[2]))
      return false;
    if (boxRow == row)
    {
      if (!stream.Read(out, row * rows))
        return false;
      out += row * rows;
    }
    else
    {
      if (!stream.Read(rowBuffer.data(), rowBuffer.size()))
        return false;
      for (std::size_t j = 0; j < rows; ++j, out += boxRow)
        std::memcpy(out, rowBuffer.data() + j * row + valueBytes * box[0], boxRow);
    }
    if (k + 1 < slices && !stream.Skip(row * (dims[1] - 1 - box[3])))
      return false;
  }
  return true;
}
} // namespace

vtkSmartPointer<vtkDataArray> InflateNIfTIVoxels(
  const std::string& fileName, int scalarType, const int wholeExtent[6], const int extent[6])
{
  int dims[3], box[6];
  vtkIdType voxels = 1;
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = wholeExtent[2 * a + 1] - wholeExtent[2 * a] + 1;
    box[2 * a] = extent[2 * a] - wholeExtent[2 * a];
    box[2 * a + 1] = extent[2 * a + 1] - wholeExtent[2 * a];
    if (dims[a] <= 0 || box[2 * a] < 0 || box[2 * a + 1] < box[2 * a] || box[2 * a + 1] >= dims[a])
      return nullptr;
    voxels *= box[2 * a + 1] - box[2 * a] + 1;
  }
  std::size_t offset = 0;
  bool swap = false;
  if (!vtksys::SystemTools::StringEndsWith(fileName, ".nii.gz") || !ReadVoxelLayout(fileName, offset, swap))
    return nullptr;
  vtkSmartPointer<vtkDataArray> array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(scalarType));
  if (!array)
    return nullptr;
  const std::size_t valueBytes = static_cast<std::size_t>(array->GetDataTypeSize());
  const std::size_t dataBytes = valueBytes * static_cast<std::size_t>(voxels);
  const bool whole = std::equal(extent, extent + 6, wholeExtent);
  unsigned char* block = nullptr;
  if (whole)
    block = InflateWhole(fileName, offset, dataBytes);
  else if ((block = static_cast<unsigned char*>(std::malloc(dataBytes))) &&
    !InflateBox(fileName, offset, valueBytes, dims, box, block))
  {
    std::free(block);
    block = nullptr;
  }
  if (!block)
    return nullptr;
  if (swap && valueBytes > 1)
    vtkByteSwap::SwapVoidRange(block, voxels, static_cast<int>(valueBytes));
  array->SetVoidArray(block, voxels, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  return array;
}

bool CountNIfTIBoundaryPerSlice(
  const std::string& fileName, int scalarType, const int wholeExtent[6], std::vector<double>& perSlice)
{
  perSlice.clear();
  std::size_t dims[3];
  for (int a = 0; a < 3; ++a)
  {
    if (wholeExtent[2 * a + 1] < wholeExtent[2 * a])
      return false;
    dims[a] = std::size_t(wholeExtent[2 * a + 1] - wholeExtent[2 * a] + 1);
  }
  const int valueBytes = vtkDataArray::GetDataTypeSize(scalarType);
  std::size_t offset = 0;
  bool swap = false; // (a value is 0 in either byte order)
  if (valueBytes <= 0 ||
    !(vtksys::SystemTools::StringEndsWith(fileName, ".nii.gz") || vtksys::SystemTools::StringEndsWith(fileName, ".nii")) ||
    !ReadVoxelLayout(fileName, offset, swap))
    return false;
  GzipStream stream(fileName);
  const std::size_t row = valueBytes * dims[0];
  std::vector<unsigned char> slice(row * dims[1]), previous(slice.size());
  std::vector<std::int64_t> counts(dims[0] + dims[1] + dims[2], 0);
  std::int64_t* const alongX = counts.data();
  std::int64_t* const alongY = alongX + dims[0];
  std::int64_t* const alongZ = alongY + dims[1];
  // Raw bytes compare equal in either byte order.
  auto differs = [valueBytes](const unsigned char* a, const unsigned char* b) {
    return std::memcmp(a, b, std::size_t(valueBytes)) != 0;
  };
  if (!stream.Skip(offset))
    return false;
  for (std::size_t k = 0; k < dims[2]; ++k)
  {
    if (!stream.Read(slice.data(), slice.size()))
      return false;
    for (std::size_t j = 0; j < dims[1]; ++j)
      for (std::size_t i = 0; i < dims[0]; ++i)
      {
        const std::size_t at = j * row + i * valueBytes;
        const unsigned char* value = slice.data() + at;
        if ((i > 0 && differs(value, value - valueBytes)) || (j > 0 && differs(value, value - row)) ||
          (k > 0 && differs(value, previous.data() + at)))
        {
          ++alongX[i];
          ++alongY[j];
          ++alongZ[k];
        }
      }
    slice.swap(previous);
  }
  perSlice.assign(counts.begin(), counts.end());
  return true;
}
