// Test of vtkCBC3DNIfTIReader's sub-extents: an int16 NIfTI-1 image whose voxel (i,j,k) holds
// (i + 7j + 31k) mod 3001 is written here as .nii and as .nii.gz (zlib's deflate), and
// z slabs at the start, middle and end, one slice, a general sub-box, the whole extent and
// pieces are asked of the reader through the pipeline. Every output must have exactly the
// asked extent and every voxel the formula's value at its index.
// With CountBoundaryPerSlice on, the reader's BOUNDARY_PER_SLICE must count the formula's
// boundary voxels (a value other than the voxel's before along x, y or z) per slice, where it is given at all (VTK's slice order, not the reversed files).
// Cases: little- and big-endian, and two left-handed files (qfac -1; an sform of negative
// determinant and no qform) where VTK's order puts file slice (nz - 1 - K) at slice K.
#include "vtkCBC3DNIfTIReader.h"

#include "CBC3DTestUtilities.h"

#include <vtkByteSwap.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationDoubleVectorKey.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtk_zlib.h>

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
// Big enough that the middle and end slabs lie past several 1 MiB reads of the stream.
constexpr int NX = 64, NY = 48, NZ = 220;

int FileValue(int i, int j, int k)
{
  return (i + 7 * j + 31 * k) % 3001;
}

enum class Handedness
{
  Right,
  QFacMinus,
  SFormMinus
};

struct Case
{
  std::string Name;
  bool BigEndian;
  Handedness Hand;
};

template <typename T>
void Put(std::vector<unsigned char>& bytes, std::size_t offset, T value, bool swap)
{
  if (swap)
  {
    vtkByteSwap::SwapVoidRange(&value, 1, sizeof(T));
  }
  std::memcpy(bytes.data() + offset, &value, sizeof(T));
}

// A single-file NIfTI-1 image: 348-byte header, 4 bytes of extension flag, int16 voxels.
std::vector<unsigned char> MakeNifti(const Case& c)
{
  const bool swap = c.BigEndian;
  std::vector<unsigned char> bytes(352 + std::size_t(2) * NX * NY * NZ, 0);
  Put<int32_t>(bytes, 0, 348, swap);
  const int16_t dim[8] = { 3, NX, NY, NZ, 1, 1, 1, 1 };
  for (int d = 0; d < 8; ++d)
  {
    Put<int16_t>(bytes, 40 + 2 * d, dim[d], swap);
  }
  Put<int16_t>(bytes, 70, 4, swap);  // DT_INT16
  Put<int16_t>(bytes, 72, 16, swap); // bitpix
  const float pixdim[4] = { c.Hand == Handedness::QFacMinus ? -1.0f : 1.0f, 1.0f, 1.0f, 1.0f };
  for (int d = 0; d < 4; ++d)
  {
    Put<float>(bytes, 76 + 4 * d, pixdim[d], swap);
  }
  Put<float>(bytes, 108, 352.0f, swap); // vox_offset
  Put<float>(bytes, 112, 1.0f, swap);   // scl_slope
  if (c.Hand == Handedness::QFacMinus)
  {
    Put<int16_t>(bytes, 252, 1, swap); // qform_code; identity quaternion
  }
  else if (c.Hand == Handedness::SFormMinus)
  {
    Put<int16_t>(bytes, 254, 1, swap); // sform_code: diag(1, 1, -1)
    const float rows[3][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, -1, 0 } };
    for (int r = 0; r < 3; ++r)
    {
      for (int col = 0; col < 4; ++col)
      {
        Put<float>(bytes, 280 + 16 * r + 4 * col, rows[r][col], swap);
      }
    }
  }
  std::memcpy(bytes.data() + 344, "n+1\0", 4);
  std::size_t at = 352;
  for (int k = 0; k < NZ; ++k)
  {
    for (int j = 0; j < NY; ++j)
    {
      for (int i = 0; i < NX; ++i, at += 2)
      {
        Put<int16_t>(bytes, at, static_cast<int16_t>(FileValue(i, j, k)), swap);
      }
    }
  }
  return bytes;
}

bool WriteFiles(const std::string& stem, const std::vector<unsigned char>& bytes)
{
  std::ofstream plain(stem + ".nii", std::ios::binary);
  plain.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  plain.close();
  gzFile gz = gzopen((stem + ".nii.gz").c_str(), "wb6");
  const bool written =
    gz && gzwrite(gz, bytes.data(), unsigned(bytes.size())) == int(bytes.size());
  return gz && gzclose(gz) == Z_OK && written && static_cast<bool>(plain);
}

// The extent's voxels against the formula; false (and the first mismatch printed) otherwise.
bool VoxelsMatch(vtkImageData* image, const int extent[6], bool reversed, const std::string& what)
{
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  const vtkIdType expected = vtkIdType(extent[1] - extent[0] + 1) *
    (extent[3] - extent[2] + 1) * (extent[5] - extent[4] + 1);
  if (!scalars || scalars->GetNumberOfTuples() != expected ||
    scalars->GetDataType() != VTK_SHORT || scalars->GetNumberOfComponents() != 1)
  {
    std::cerr << what << ": no int16 scalars of " << expected << " values" << std::endl;
    return false;
  }
  const auto* values = static_cast<const int16_t*>(scalars->GetVoidPointer(0));
  vtkIdType at = 0;
  for (int k = extent[4]; k <= extent[5]; ++k)
  {
    const int fileK = reversed ? NZ - 1 - k : k;
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      for (int i = extent[0]; i <= extent[1]; ++i, ++at)
      {
        if (values[at] != FileValue(i, j, fileK))
        {
          std::cerr << what << ": voxel (" << i << "," << j << "," << k << ") holds "
                    << values[at] << ", not " << FileValue(i, j, fileK) << std::endl;
          return false;
        }
      }
    }
  }
  return true;
}

bool SameExtent(const int* a, const int* b)
{
  return std::equal(a, a + 6, b);
}

void CheckExtents(const std::string& path, bool reversed, bool fastPath)
{
  vtkNew<cbc3dtest::MessageCatcher> errors;
  auto reader = vtkSmartPointer<vtkCBC3DNIfTIReader>::New();
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  // Each extent lies outside the one before, so the reader runs for each: the executive keeps
  // an output that already holds the asked extent.
  const std::array<std::array<int, 6>, 8> asked = { {
    { 0, NX - 1, 0, NY - 1, 0, NZ / 3 - 1 },            // first slab
    { 0, NX - 1, 0, NY - 1, NZ / 3, 2 * NZ / 3 - 1 },   // middle slab
    { 0, NX - 1, 0, NY - 1, 2 * NZ / 3, NZ - 1 },       // last slab
    { 0, NX - 1, 0, NY - 1, 101, 101 },                 // one slice
    { 5, 40, 3, 30, 50, 170 },                          // a sub-box
    { 0, NX - 1, 0, NY - 1, 0, 0 },                     // the first slice
    { 0, NX - 1, 7, 7, NZ - 1, NZ - 1 },                // one row of the last slice
    { 0, NX - 1, 0, NY - 1, 0, NZ - 1 },                // the whole image
  } };
  for (const auto& ask : asked)
  {
    std::string what = path + " extent";
    for (const int e : ask)
    {
      what += " " + std::to_string(e);
    }
    CHECK(reader->UpdateExtent(ask.data()) == 1);
    vtkImageData* image = reader->GetOutput();
    CHECK(SameExtent(image->GetExtent(), ask.data()));
    CHECK(VoxelsMatch(image, ask.data(), reversed, what));
    const bool whole = SameExtent(ask.data(), std::array<int, 6>{ 0, NX - 1, 0, NY - 1, 0, NZ - 1 }.data());
    if (fastPath)
    {
      // The reader's own inflater, not vtkNIFTIImageReader: libdeflate for the whole image,
      // zlib's stream (keeping only the asked slices) for a part.
      CHECK(reader->GetInflatedAtOnce() == whole);
      CHECK(reader->GetInflatedSubExtent() == !whole);
    }
  }
  CHECK(errors->Text.empty());
  if (!errors->Text.empty())
  {
    std::cerr << path << ": " << errors->Text << std::endl;
  }
}

// Pieces through the executive, as a parallel pipeline asks them: z slabs here (VTK splits the
// longest axis), each smaller than the image, and together they hold every voxel.
void CheckPieces(const std::string& path, bool reversed)
{
  auto reader = vtkSmartPointer<vtkCBC3DNIfTIReader>::New();
  reader->SetFileName(path.c_str());
  const int pieces = 3;
  std::vector<int> covered(NZ, 0);
  for (int piece = 0; piece < pieces; ++piece)
  {
    CHECK(reader->UpdatePiece(piece, pieces, 0) == 1);
    vtkImageData* image = reader->GetOutput();
    const int* extent = image->GetExtent();
    CHECK(extent[0] == 0 && extent[1] == NX - 1 && extent[2] == 0 && extent[3] == NY - 1);
    CHECK(extent[5] - extent[4] + 1 < NZ);
    CHECK(VoxelsMatch(image, extent, reversed, path + " piece " + std::to_string(piece)));
    for (int k = std::max(extent[4], 0); k <= std::min(extent[5], NZ - 1); ++k)
    {
      covered[k] = 1;
    }
  }
  CHECK(std::count(covered.begin(), covered.end(), 1) == NZ);
}

// The boundary voxels per slice from the header pass, against the formula's.
void CheckBoundaryPerSlice(const std::string& path, bool reversed)
{
  auto reader = vtkSmartPointer<vtkCBC3DNIfTIReader>::New();
  reader->SetFileName(path.c_str());
  reader->CountBoundaryPerSliceOn();
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  vtkInformationDoubleVectorKey* key = vtkCBC3DNIfTIReader::BOUNDARY_PER_SLICE();
  if (reversed)
  {
    CHECK(!info->Has(key)); // counted in the file's order, which is not VTK's here
    return;
  }
  std::vector<double> expected(NX + NY + NZ, 0.0);
  for (int k = 0; k < NZ; ++k)
    for (int j = 0; j < NY; ++j)
      for (int i = 0; i < NX; ++i)
        if ((i > 0 && FileValue(i, j, k) != FileValue(i - 1, j, k)) ||
          (j > 0 && FileValue(i, j, k) != FileValue(i, j - 1, k)) ||
          (k > 0 && FileValue(i, j, k) != FileValue(i, j, k - 1)))
        {
          ++expected[i];
          ++expected[NX + j];
          ++expected[NX + NY + k];
        }
  CHECK(expected[0] == NY * NZ - 1); // all but the first voxel, which has none before it
  CHECK(info->Has(key) && info->Length(key) == NX + NY + NZ);
  if (info->Has(key) && info->Length(key) == NX + NY + NZ)
  {
    CHECK(std::equal(expected.begin(), expected.end(), info->Get(key)));
  }
}
} // namespace

int TestCBC3DNIfTIReaderPieces(int, char*[])
{
  const char* env = std::getenv("CBC3D_TEST_OUTPUT");
  std::string dir = env && *env ? env : "/tmp";
  dir += "/TestCBC3DNIfTIReaderPieces";
  vtksys::SystemTools::MakeDirectory(dir);
  const Case cases[] = {
    { "little", false, Handedness::Right },
    { "big", true, Handedness::Right },
    { "qfac-minus", false, Handedness::QFacMinus },
    { "sform-minus", false, Handedness::SFormMinus },
  };
  for (const Case& c : cases)
  {
    const std::string stem = dir + "/" + c.Name;
    CHECK(WriteFiles(stem, MakeNifti(c)));
    const bool reversed = c.Hand != Handedness::Right;
    CheckExtents(stem + ".nii", reversed, false);
    CheckExtents(stem + ".nii.gz", reversed, !reversed);
    CheckPieces(stem + ".nii", reversed);
    CheckPieces(stem + ".nii.gz", reversed);
    CheckBoundaryPerSlice(stem + ".nii", reversed);
    CheckBoundaryPerSlice(stem + ".nii.gz", reversed);
  }
  return cbc3dtest::Finish();
}
