// Test of vtkCBC3DNIfTIReader: small NIfTI-1 files are written here byte by byte (the 348-byte
// header of the NIfTI-1 standard), read back, and every voxel's position from
// vtkImageData::TransformIndexToPhysicalPoint is compared with the position that the standard's
// formulas give for that voxel's (i,j,k) in the file:
//   sform ("method 3"):  x = srow_x . (i,j,k,1), y = srow_y . (i,j,k,1), z = srow_z . (i,j,k,1)
//   qform ("method 2"):  [x y z] = R [pixdim1*i, pixdim2*j, qfac*pixdim3*k] + qoffset
//   none  ("method 1"):  [x y z] = [pixdim1*i, pixdim2*j, pixdim3*k]
// Each voxel holds a distinct value (1 + its file index), so a voxel is found in the output
// even where VTK reverses the slice order (qfac = -1).
#include "vtkCBC3DNIfTIReader.h"

#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkExecutive.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMath.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
// The NIfTI-1 header fields this test sets; everything else is written as zero.
struct Header
{
  std::array<int16_t, 3> Dim = { { 4, 3, 5 } };
  std::array<float, 4> PixDim = { { 1.0f, 1.0f, 1.0f, 1.0f } }; // PixDim[0] = qfac
  int16_t QFormCode = 0;
  int16_t SFormCode = 0;
  float QuaternB = 0.0f, QuaternC = 0.0f, QuaternD = 0.0f;
  float QOffset[3] = { 0.0f, 0.0f, 0.0f };
  float SRow[3][4] = { { 0.0f, 0.0f, 0.0f, 0.0f }, { 0.0f, 0.0f, 0.0f, 0.0f },
    { 0.0f, 0.0f, 0.0f, 0.0f } };
};

template <typename T>
void Put(std::vector<unsigned char>& bytes, size_t offset, T value)
{
  std::memcpy(bytes.data() + offset, &value, sizeof(T)); // native order, which NIfTI allows
}

// A .nii file: 348-byte header, 4 bytes of extension flag, int16 voxels from offset 352.
std::vector<unsigned char> MakeNifti(const Header& h)
{
  const int n = h.Dim[0] * h.Dim[1] * h.Dim[2];
  std::vector<unsigned char> bytes(352 + 2 * n, 0);
  Put<int32_t>(bytes, 0, 348);         // sizeof_hdr
  Put<int16_t>(bytes, 40, 3);          // dim[0]
  for (int a = 0; a < 3; ++a)
  {
    Put<int16_t>(bytes, 42 + 2 * a, h.Dim[a]); // dim[1..3]
  }
  for (int a = 4; a < 8; ++a)
  {
    Put<int16_t>(bytes, 40 + 2 * a, 1); // dim[4..7]
  }
  Put<int16_t>(bytes, 70, 4);  // datatype: DT_INT16
  Put<int16_t>(bytes, 72, 16); // bitpix
  for (int a = 0; a < 4; ++a)
  {
    Put<float>(bytes, 76 + 4 * a, h.PixDim[a]); // pixdim[0..3]
  }
  Put<float>(bytes, 108, 352.0f); // vox_offset
  Put<float>(bytes, 112, 1.0f);   // scl_slope
  Put<int16_t>(bytes, 252, h.QFormCode);
  Put<int16_t>(bytes, 254, h.SFormCode);
  Put<float>(bytes, 256, h.QuaternB);
  Put<float>(bytes, 260, h.QuaternC);
  Put<float>(bytes, 264, h.QuaternD);
  for (int a = 0; a < 3; ++a)
  {
    Put<float>(bytes, 268 + 4 * a, h.QOffset[a]);
    for (int c = 0; c < 4; ++c)
    {
      Put<float>(bytes, 280 + 16 * a + 4 * c, h.SRow[a][c]);
    }
  }
  std::memcpy(bytes.data() + 344, "n+1\0", 4); // magic
  for (int index = 0; index < n; ++index)
  {
    Put<int16_t>(bytes, 352 + 2 * index, static_cast<int16_t>(1 + index));
  }
  return bytes;
}

uint32_t Crc32(const std::vector<unsigned char>& bytes)
{
  uint32_t crc = 0xFFFFFFFFu;
  for (const unsigned char byte : bytes)
  {
    crc ^= byte;
    for (int bit = 0; bit < 8; ++bit)
    {
      crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
  }
  return ~crc;
}

// A gzip member (RFC 1952) whose deflate stream (RFC 1951) is made of stored blocks.
std::vector<unsigned char> Gzip(const std::vector<unsigned char>& data)
{
  std::vector<unsigned char> out = { 0x1f, 0x8b, 8, 0, 0, 0, 0, 0, 0, 0xff };
  size_t offset = 0;
  do
  {
    const size_t length = std::min<size_t>(65535, data.size() - offset);
    const bool last = offset + length == data.size();
    out.push_back(last ? 1 : 0); // BFINAL, BTYPE = 00 (stored)
    out.push_back(static_cast<unsigned char>(length & 0xff));
    out.push_back(static_cast<unsigned char>(length >> 8));
    out.push_back(static_cast<unsigned char>(~length & 0xff));
    out.push_back(static_cast<unsigned char>((~length >> 8) & 0xff));
    out.insert(out.end(), data.begin() + offset, data.begin() + offset + length);
    offset += length;
  } while (offset < data.size());
  const uint32_t trailer[2] = { Crc32(data), static_cast<uint32_t>(data.size()) };
  for (const uint32_t word : trailer)
  {
    for (int b = 0; b < 4; ++b)
    {
      out.push_back(static_cast<unsigned char>((word >> (8 * b)) & 0xff));
    }
  }
  return out;
}

bool WriteFile(const std::string& path, const std::vector<unsigned char>& bytes)
{
  std::ofstream file(path, std::ios::binary);
  file.write(
    reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(file);
}

// World position of file voxel (i,j,k) from the header alone, by the NIfTI-1 standard.
void ExpectedWorld(const Header& h, int i, int j, int k, double world[3])
{
  if (h.SFormCode > 0)
  {
    for (int r = 0; r < 3; ++r)
    {
      world[r] = double(h.SRow[r][0]) * i + double(h.SRow[r][1]) * j +
        double(h.SRow[r][2]) * k + double(h.SRow[r][3]);
    }
    return;
  }
  const double p[3] = { double(h.PixDim[1]) * i, double(h.PixDim[2]) * j,
    double(h.PixDim[3]) * k };
  if (h.QFormCode > 0)
  {
    const double b = h.QuaternB, c = h.QuaternC, d = h.QuaternD;
    const double a = std::sqrt(std::max(0.0, 1.0 - (b * b + c * c + d * d)));
    const double qfac = h.PixDim[0] < 0 ? -1.0 : 1.0;
    const double R[3][3] = { { a * a + b * b - c * c - d * d, 2 * b * c - 2 * a * d,
                               2 * b * d + 2 * a * c },
      { 2 * b * c + 2 * a * d, a * a + c * c - b * b - d * d, 2 * c * d - 2 * a * b },
      { 2 * b * d - 2 * a * c, 2 * c * d + 2 * a * b, a * a + d * d - c * c - b * b } };
    for (int r = 0; r < 3; ++r)
    {
      world[r] = R[r][0] * p[0] + R[r][1] * p[1] + R[r][2] * qfac * p[2] + double(h.QOffset[r]);
    }
    return;
  }
  for (int r = 0; r < 3; ++r)
  {
    world[r] = p[r];
  }
}

// Sets the header's sform to rotation(axis, angle) * diag(pixdim) + translation.
void SetRotatedSForm(Header& h, const double axis[3], double degrees, const double t[3])
{
  double quat[4], R[3][3];
  double n[3] = { axis[0], axis[1], axis[2] };
  vtkMath::Normalize(n);
  const double half = vtkMath::RadiansFromDegrees(degrees) / 2;
  quat[0] = std::cos(half);
  for (int a = 0; a < 3; ++a)
  {
    quat[a + 1] = std::sin(half) * n[a];
  }
  vtkMath::QuaternionToMatrix3x3(quat, R);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      h.SRow[r][c] = static_cast<float>(R[r][c] * h.PixDim[c + 1]);
    }
    h.SRow[r][3] = static_cast<float>(t[r]);
  }
}

class MessageObserver : public vtkCommand
{
public:
  static MessageObserver* New() { return new MessageObserver; }
  void Execute(vtkObject*, unsigned long event, void* callData) override
  {
    const std::string text = callData ? static_cast<const char*>(callData) : "";
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings).push_back(text);
  }
  void Clear()
  {
    this->Errors.clear();
    this->Warnings.clear();
  }
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
};

struct Checker
{
  int Failures = 0;
  void Check(bool ok, const std::string& what)
  {
    if (!ok)
    {
      std::cerr << "FAILED: " << what << "\n";
      ++this->Failures;
    }
  }
};

vtkSmartPointer<vtkCBC3DNIfTIReader> MakeReader(MessageObserver* observer)
{
  auto reader = vtkSmartPointer<vtkCBC3DNIfTIReader>::New();
  reader->AddObserver(vtkCommand::ErrorEvent, observer);
  reader->AddObserver(vtkCommand::WarningEvent, observer);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  return reader;
}

// Reads `path` (holding header h) and checks every voxel's position, the frame rule, the
// direction's determinant (0: not checked), the scalars and the pipeline information.
void CheckCase(Checker& check, const std::string& name, const std::string& path, const Header& h,
  const char* frameSource, double determinant, int warnings)
{
  vtkNew<MessageObserver> observer;
  auto reader = MakeReader(observer);
  check.Check(reader->CanReadFile(path.c_str()) != 0, name + ": CanReadFile");
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  double infoDirection[9] = { 0 };
  vtkInformation* outInfo = reader->GetOutputInformation(0);
  const bool hasDirection = outInfo->Has(vtkDataObject::DIRECTION()) != 0;
  check.Check(hasDirection, name + ": DIRECTION in the output information");
  if (hasDirection)
  {
    outInfo->Get(vtkDataObject::DIRECTION(), infoDirection);
  }
  reader->Update();
  check.Check(observer->Errors.empty(), name + ": no error");
  check.Check(static_cast<int>(observer->Warnings.size()) == warnings,
    name + ": " + std::to_string(warnings) + " warning(s), got " +
      std::to_string(observer->Warnings.size()));
  check.Check(std::string(reader->GetFrameSource()) == frameSource,
    name + ": frame source " + frameSource + ", got " + reader->GetFrameSource());

  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  check.Check(dims[0] == h.Dim[0] && dims[1] == h.Dim[1] && dims[2] == h.Dim[2],
    name + ": dimensions");
  for (int a = 0; a < 3; ++a)
  {
    check.Check(std::fabs(image->GetSpacing()[a] - std::fabs(h.PixDim[a + 1])) < 1e-12,
      name + ": spacing = |pixdim|");
  }
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  check.Check(scalars != nullptr, name + ": active scalars");
  if (!scalars)
  {
    return;
  }
  check.Check(scalars->GetDataType() == VTK_SHORT, name + ": int16 voxels stay int16");
  check.Check(scalars->GetName() && *scalars->GetName(), name + ": scalars have a name");
  const double* direction = image->GetDirectionMatrix()->GetData();
  double directionGap = 0.0;
  for (int e = 0; e < 9; ++e)
  {
    directionGap = std::max(directionGap, std::fabs(direction[e] - infoDirection[e]));
  }
  check.Check(directionGap < 1e-12, name + ": information and data directions agree");
  const double det = image->GetDirectionMatrix()->Determinant();
  check.Check(std::fabs(std::fabs(det) - 1.0) < 1e-5, name + ": direction is orthonormal");
  if (determinant != 0)
  {
    check.Check(std::fabs(det - determinant) < 1e-5,
      name + ": direction determinant " + std::to_string(determinant) + ", got " +
        std::to_string(det));
  }

  // Output index of every value, then the position of every file voxel.
  const int n = h.Dim[0] * h.Dim[1] * h.Dim[2];
  std::map<long, std::array<int, 3>> where;
  for (int K = 0; K < dims[2]; ++K)
  {
    for (int J = 0; J < dims[1]; ++J)
    {
      for (int I = 0; I < dims[0]; ++I)
      {
        const int ijk[3] = { I, J, K };
        const vtkIdType id = image->ComputePointId(const_cast<int*>(ijk));
        where[static_cast<long>(scalars->GetTuple1(id))] = { { I, J, K } };
      }
    }
  }
  check.Check(static_cast<int>(where.size()) == n, name + ": every voxel value is read once");
  double worst = 0.0;
  for (int index = 0; index < n; ++index)
  {
    const int i = index % h.Dim[0], j = (index / h.Dim[0]) % h.Dim[1],
              k = index / (h.Dim[0] * h.Dim[1]);
    const auto found = where.find(1 + index);
    if (found == where.end())
    {
      check.Check(false, name + ": value " + std::to_string(1 + index) + " missing");
      continue;
    }
    double expected[3], actual[3];
    ExpectedWorld(h, i, j, k, expected);
    image->TransformIndexToPhysicalPoint(found->second.data(), actual);
    worst = std::max(worst, std::sqrt(vtkMath::Distance2BetweenPoints(expected, actual)));
  }
  check.Check(worst < 1e-6, name + ": voxel world positions (worst error " +
      std::to_string(worst) + " mm)");
  std::cout << name << ": frame " << reader->GetFrameSource() << ", det " << det
            << ", worst position error " << worst << " mm\n";
}

// The file in big-endian order: every header field MakeNifti sets, and the int16 voxels.
std::vector<unsigned char> BigEndian(std::vector<unsigned char> bytes)
{
  auto swap = [&](size_t offset, size_t size, size_t count) {
    for (size_t i = 0; i < count; ++i)
    {
      std::reverse(bytes.begin() + offset + i * size, bytes.begin() + offset + (i + 1) * size);
    }
  };
  swap(0, 4, 1);   // sizeof_hdr
  swap(40, 2, 8);  // dim
  swap(70, 2, 2);  // datatype, bitpix
  swap(76, 4, 8);  // pixdim
  swap(108, 4, 2); // vox_offset, scl_slope
  swap(252, 2, 2); // qform_code, sform_code
  swap(256, 4, 18); // quatern_b .. srow_z
  swap(352, 2, (bytes.size() - 352) / 2);
  return bytes;
}

// The same voxels read from a .nii (vtkNIFTIImageReader) and a .nii.gz: the same image.
void CheckInflatedAtOnce(Checker& check, const std::string& name, const std::string& dir,
  const std::vector<unsigned char>& nifti, const std::vector<unsigned char>& gzipped, bool atOnce)
{
  const std::string plain = dir + "/" + name + ".nii", packed = dir + "/" + name + ".nii.gz";
  check.Check(WriteFile(plain, nifti) && WriteFile(packed, gzipped), name + ": write");
  vtkNew<MessageObserver> observer;
  auto a = MakeReader(observer), b = MakeReader(observer);
  a->SetFileName(plain.c_str());
  b->SetFileName(packed.c_str());
  a->Update();
  b->Update();
  check.Check(observer->Errors.empty(), name + ": no error");
  check.Check(!a->GetInflatedAtOnce() && b->GetInflatedAtOnce() == atOnce,
    name + (atOnce ? ": the .nii.gz inflated at once" : ": the .nii.gz left to VTK's reader"));
  vtkImageData* x = a->GetOutput();
  vtkImageData* y = b->GetOutput();
  vtkDataArray* u = x->GetPointData()->GetScalars();
  vtkDataArray* v = y->GetPointData()->GetScalars();
  bool same = u && v && u->GetDataType() == v->GetDataType() && u->GetNumberOfTuples() == v->GetNumberOfTuples() &&
    u->GetNumberOfComponents() == v->GetNumberOfComponents() && std::string(u->GetName()) == v->GetName();
  for (int e = 0; same && e < 6; ++e)
  {
    same = x->GetExtent()[e] == y->GetExtent()[e];
  }
  for (int e = 0; same && e < 3; ++e)
  {
    same = x->GetOrigin()[e] == y->GetOrigin()[e] && x->GetSpacing()[e] == y->GetSpacing()[e];
  }
  for (int e = 0; same && e < 9; ++e)
  {
    same = x->GetDirectionMatrix()->GetData()[e] == y->GetDirectionMatrix()->GetData()[e];
  }
  for (vtkIdType t = 0; same && t < u->GetNumberOfTuples(); ++t)
  {
    same = u->GetTuple1(t) == v->GetTuple1(t);
  }
  check.Check(same, name + ": the same frame, type, name and voxels as the .nii");
}

// Reading `path` must fail with an error that names the file, without crashing.
void CheckFailure(Checker& check, const std::string& name, const char* path)
{
  vtkNew<MessageObserver> observer;
  auto reader = MakeReader(observer);
  if (path)
  {
    check.Check(reader->CanReadFile(path) == 0, name + ": CanReadFile is false");
  }
  reader->SetFileName(path);
  reader->Update();
  bool named = false;
  for (const std::string& error : observer->Errors)
  {
    named = named || (path && error.find(path) != std::string::npos) ||
      (!path && error.find("vtkCBC3DNIfTIReader") != std::string::npos);
  }
  check.Check(!observer->Errors.empty(), name + ": an error is reported");
  check.Check(named, name + ": the error names the file");
  check.Check(reader->GetOutput()->GetNumberOfPoints() == 0, name + ": empty output");
  check.Check(std::string(reader->GetFrameSource()).empty(), name + ": no frame source");
  if (!observer->Errors.empty())
  {
    std::cout << name << ": " << observer->Errors[0];
  }
}
} // namespace

int TestCBC3DNIfTIReader(int, char*[])
{
  const char* env = std::getenv("CBC3D_TEST_OUTPUT");
  const char* tmp = std::getenv("TMPDIR");
  std::string dir = env && *env ? env : (tmp && *tmp ? tmp : "/tmp");
  dir += "/TestCBC3DNIfTIReader";
  vtksys::SystemTools::MakeDirectory(dir);
  Checker check;

  // (a) sform: a rotation of 30 degrees about an oblique axis, a translation, anisotropic
  // spacing. A different qform is present too: the sform must win.
  Header a;
  a.PixDim = { { 1.0f, 0.8f, 1.25f, 2.0f } };
  const double axisA[3] = { 1.0, 2.0, 3.0 }, tA[3] = { -12.5, 30.25, 7.0 };
  SetRotatedSForm(a, axisA, 30.0, tA);
  a.SFormCode = 2;
  a.QFormCode = 1;
  a.QOffset[0] = 100.0f;
  const std::string pathA = dir + "/sform_oblique.nii";
  check.Check(WriteFile(pathA, MakeNifti(a)), "write " + pathA);
  CheckCase(check, "(a) sform oblique", pathA, a, "sform", 1.0, 0);

  // (b) qform only, qfac = -1 (left-handed ijk): VTK reverses the slices. The srows hold
  // values that must be ignored (sform_code 0).
  Header b;
  b.PixDim = { { -1.0f, 0.9f, 1.1f, 1.7f } };
  b.QFormCode = 1;
  b.QuaternB = 0.1f;
  b.QuaternC = 0.2f;
  b.QuaternD = 0.3f;
  b.QOffset[0] = 10.0f;
  b.QOffset[1] = -20.0f;
  b.QOffset[2] = 30.0f;
  b.SRow[0][0] = 5.0f;
  b.SRow[1][3] = 99.0f;
  const std::string pathB = dir + "/qform_qfac_neg.nii";
  check.Check(WriteFile(pathB, MakeNifti(b)), "write " + pathB);
  CheckCase(check, "(b) qform qfac=-1", pathB, b, "qform", 1.0, 0);
  {
    // The class documents that slice K holds the file's slice dim[3]-1-K when qfac = -1.
    vtkNew<vtkCBC3DNIfTIReader> reader;
    reader->SetFileName(pathB.c_str());
    reader->Update();
    vtkDataArray* s = reader->GetOutput()->GetPointData()->GetScalars();
    const int firstOfLastSlice = 1 + b.Dim[0] * b.Dim[1] * (b.Dim[2] - 1);
    check.Check(s && s->GetTuple1(0) == firstOfLastSlice, "(b) slice order reversed");
  }

  // (c1) an sform that is a reflection (LAS: x flipped), no qform: VTK reverses the slices,
  // which turns the index-to-world map into a rotation; positions are the header's.
  Header c;
  c.PixDim = { { 1.0f, 1.5f, 1.0f, 2.5f } };
  c.SFormCode = 1;
  c.SRow[0][0] = -1.5f;
  c.SRow[0][3] = 40.0f;
  c.SRow[1][1] = 1.0f;
  c.SRow[1][3] = -8.0f;
  c.SRow[2][2] = 2.5f;
  c.SRow[2][3] = 3.0f;
  const std::string pathC = dir + "/sform_LAS.nii";
  check.Check(WriteFile(pathC, MakeNifti(c)), "write " + pathC);
  CheckCase(check, "(c1) sform LAS", pathC, c, "sform", 0.0, 0);

  // (c2) the same reflecting sform beside a qform with qfac = +1: VTK keeps the slice order,
  // so the reflection must reach the output as a direction with determinant -1. VTK warns that
  // the sform is flipped compared to the qform (one warning).
  Header c2 = c;
  c2.QFormCode = 1;
  c2.PixDim[0] = 1.0f;
  const std::string pathC2 = dir + "/sform_LAS_qform_RAS.nii";
  check.Check(WriteFile(pathC2, MakeNifti(c2)), "write " + pathC2);
  CheckCase(check, "(c2) sform LAS + qform", pathC2, c2, "sform", -1.0, 1);

  // (d) no qform or sform code: voxel size alone (the srows and quaternion must be ignored).
  Header d;
  d.PixDim = { { 1.0f, 0.5f, 0.75f, 3.0f } };
  d.QuaternB = 0.5f;
  d.SRow[0][0] = 7.0f;
  d.SRow[2][3] = -50.0f;
  const std::string pathD = dir + "/no_frame.nii";
  check.Check(WriteFile(pathD, MakeNifti(d)), "write " + pathD);
  CheckCase(check, "(d) voxel size", pathD, d, "voxel size", 1.0, 0);

  // (e) .nii.gz: a rotated qform with qfac = +1, gzip-compressed.
  Header e;
  e.Dim = { { 3, 5, 4 } };
  e.PixDim = { { 1.0f, 1.2f, 0.6f, 2.2f } };
  e.QFormCode = 2;
  e.QuaternB = -0.3f;
  e.QuaternC = 0.5f;
  e.QuaternD = 0.2f;
  e.QOffset[0] = -90.5f;
  e.QOffset[1] = 120.0f;
  e.QOffset[2] = -64.0f;
  const std::string pathE = dir + "/qform_rotated.nii.gz";
  check.Check(WriteFile(pathE, Gzip(MakeNifti(e))), "write " + pathE);
  CheckCase(check, "(e) nii.gz qform", pathE, e, "qform", 1.0, 0);

  // (g) an sform with a shear beside a qform: the qform is used, with a warning.
  Header g = e;
  g.SFormCode = 1;
  g.SRow[0][0] = 1.2f;
  g.SRow[0][1] = 0.3f;
  g.SRow[1][1] = 0.6f;
  g.SRow[2][2] = 2.2f;
  const std::string pathG = dir + "/sform_shear_qform.nii";
  check.Check(WriteFile(pathG, MakeNifti(g)), "write " + pathG);
  Header gExpected = g;
  gExpected.SFormCode = 0; // the expected positions are the qform's
  CheckCase(check, "(g) sheared sform, qform", pathG, gExpected, "qform", 1.0, 1);

  // (f) errors: no file name, a missing file, a file that is not NIfTI, a sheared sform with
  // no qform to fall back on.
  CheckFailure(check, "(f) no file name", nullptr);
  const std::string missing = dir + "/no_such_file.nii.gz";
  vtksys::SystemTools::RemoveFile(missing);
  CheckFailure(check, "(f) missing file", missing.c_str());
  const std::string text = dir + "/not_nifti.nii";
  const std::string words = "This is not a NIfTI file, only a line of text.\n";
  check.Check(WriteFile(text, std::vector<unsigned char>(words.begin(), words.end())),
    "write " + text);
  CheckFailure(check, "(f) not NIfTI", text.c_str());
  Header shear = g;
  shear.QFormCode = 0;
  const std::string pathShear = dir + "/sform_shear_only.nii";
  check.Check(WriteFile(pathShear, MakeNifti(shear)), "write " + pathShear);
  {
    vtkNew<MessageObserver> observer;
    auto reader = MakeReader(observer);
    reader->SetFileName(pathShear.c_str());
    reader->Update();
    check.Check(!observer->Errors.empty() &&
        observer->Errors[0].find(pathShear) != std::string::npos &&
        observer->Errors[0].find("shear") != std::string::npos,
      "(f) sheared sform without qform: error naming the file and the shear");
    check.Check(reader->GetOutput()->GetNumberOfPoints() == 0, "(f) sheared sform: empty output");
  }

  // (h) a header that claims far more voxels than its file holds (30000^3 int16 in 472 bytes;
  // found by the NIfTI fuzzer: the inner reader allocated the claimed 54 TB and the cbc3d
  // command aborted): one error naming the file, and no read.
  std::vector<unsigned char> huge = MakeNifti(Header());
  for (int a = 0; a < 3; ++a)
  {
    Put<int16_t>(huge, 42 + 2 * a, 30000);
  }
  const std::string pathHuge = dir + "/claims_huge_image.nii";
  check.Check(WriteFile(pathHuge, huge), "write " + pathHuge);
  {
    vtkNew<MessageObserver> observer;
    auto reader = MakeReader(observer);
    reader->SetFileName(pathHuge.c_str());
    reader->Update();
    check.Check(observer->Errors.size() >= 1 &&
        observer->Errors[0].find(pathHuge) != std::string::npos &&
        observer->Errors[0].find("30000 x 30000 x 30000 voxels") != std::string::npos,
      "(h) header claiming 30000^3 voxels: error naming the file and the size");
    check.Check(reader->GetOutput()->GetNumberOfPoints() == 0, "(h) huge claim: empty output");
  }

  // (i) a datatype code NIfTI does not define (25973; found by the NIfTI fuzzer: VTK's reader
  // crashed on it): one error naming the file and the code.
  std::vector<unsigned char> badType = MakeNifti(Header());
  Put<int16_t>(badType, 70, 25973);
  const std::string pathBadType = dir + "/unknown_datatype.nii";
  check.Check(WriteFile(pathBadType, badType), "write " + pathBadType);
  {
    vtkNew<MessageObserver> observer;
    auto reader = MakeReader(observer);
    reader->SetFileName(pathBadType.c_str());
    reader->Update();
    check.Check(observer->Errors.size() >= 1 &&
        observer->Errors[0].find(pathBadType) != std::string::npos &&
        observer->Errors[0].find("datatype 25973") != std::string::npos,
      "(i) unknown datatype: error naming the file and the code");
    check.Check(reader->GetOutput()->GetNumberOfPoints() == 0, "(i) unknown datatype: empty output");
  }

  // (j) dim[3] = 0: no voxels along z (found by the NIfTI fuzzer: VTK's reader wrote past its
  // buffer): one error naming the file.
  std::vector<unsigned char> flat = MakeNifti(Header());
  Put<int16_t>(flat, 46, 0);
  const std::string pathFlat = dir + "/no_slices.nii";
  check.Check(WriteFile(pathFlat, flat), "write " + pathFlat);
  {
    vtkNew<MessageObserver> observer;
    auto reader = MakeReader(observer);
    reader->SetFileName(pathFlat.c_str());
    reader->Update();
    check.Check(observer->Errors.size() >= 1 &&
        observer->Errors[0].find(pathFlat) != std::string::npos &&
        observer->Errors[0].find("no voxels along an axis") != std::string::npos,
      "(j) dim[3] = 0: error naming the file");
    check.Check(reader->GetOutput()->GetNumberOfPoints() == 0, "(j) dim[3] = 0: empty output");
  }

  // (j2) dim[0] = 7 with dim[5] = 0: a declared axis with no voxels beyond the third (found by
  // the NIfTI fuzzer: VTK's reader divided by zero): one error naming the file.
  std::vector<unsigned char> noComponents = MakeNifti(Header());
  Put<int16_t>(noComponents, 40, 7);
  Put<int16_t>(noComponents, 48, 1);
  Put<int16_t>(noComponents, 50, 0);
  Put<int16_t>(noComponents, 52, 1);
  Put<int16_t>(noComponents, 54, 1);
  const std::string pathNoComponents = dir + "/no_components.nii";
  check.Check(WriteFile(pathNoComponents, noComponents), "write " + pathNoComponents);
  {
    vtkNew<MessageObserver> observer;
    auto reader = MakeReader(observer);
    reader->SetFileName(pathNoComponents.c_str());
    reader->Update();
    check.Check(observer->Errors.size() >= 1 &&
        observer->Errors[0].find(pathNoComponents) != std::string::npos &&
        observer->Errors[0].find("dim[5] is 0") != std::string::npos,
      "(j2) dim[5] = 0 under dim[0] = 7: error naming the file and the axis");
    check.Check(reader->GetOutput()->GetNumberOfPoints() == 0, "(j2) empty output");
  }

  // (k) sizeof_hdr 0 beside the NIfTI-1 magic (found by the NIfTI fuzzer: VTK's reader read
  // it and crashed on its datatype): one error naming the file and the field.
  std::vector<unsigned char> noSize = MakeNifti(Header());
  Put<int32_t>(noSize, 0, 0);
  const std::string pathNoSize = dir + "/zero_sizeof_hdr.nii";
  check.Check(WriteFile(pathNoSize, noSize), "write " + pathNoSize);
  {
    vtkNew<MessageObserver> observer;
    auto reader = MakeReader(observer);
    reader->SetFileName(pathNoSize.c_str());
    reader->Update();
    check.Check(observer->Errors.size() >= 1 &&
        observer->Errors[0].find(pathNoSize) != std::string::npos &&
        observer->Errors[0].find("sizeof_hdr is 0") != std::string::npos,
      "(k) sizeof_hdr 0: error naming the file and the field");
    check.Check(reader->GetOutput()->GetNumberOfPoints() == 0, "(k) sizeof_hdr 0: empty output");
  }

  // (l) A .nii.gz is inflated at once where it is one volume stored with qfac +1, in either
  // byte order and in one gzip member or several, and gives what the .nii gives; slices stored
  // in reverse (qfac -1) are left to VTK's reader.
  {
    Header l;
    l.Dim = { { 9, 7, 5 } };
    l.PixDim = { { 1.0f, 0.5f, 0.75f, 2.0f } };
    l.QFormCode = 1;
    l.QuaternB = 0.25f;
    l.QOffset[0] = -3.0f;
    const std::vector<unsigned char> nifti = MakeNifti(l);
    CheckInflatedAtOnce(check, "(l) little-endian", dir, nifti, Gzip(nifti), true);
    CheckInflatedAtOnce(check, "(l) big-endian", dir, BigEndian(nifti), Gzip(BigEndian(nifti)), true);
    std::vector<unsigned char> members = Gzip({ nifti.begin(), nifti.begin() + 500 });
    const std::vector<unsigned char> rest = Gzip({ nifti.begin() + 500, nifti.end() });
    members.insert(members.end(), rest.begin(), rest.end());
    CheckInflatedAtOnce(check, "(l) two gzip members", dir, nifti, members, true);
    l.PixDim[0] = -1.0f;
    const std::vector<unsigned char> reversed = MakeNifti(l);
    CheckInflatedAtOnce(check, "(l) qfac -1", dir, reversed, Gzip(reversed), false);
  }

  // PrintSelf.
  {
    vtkNew<vtkCBC3DNIfTIReader> reader;
    reader->SetFileName(pathA.c_str());
    reader->Update();
    std::ostringstream os;
    reader->Print(os);
    check.Check(os.str().find("FrameSource: sform") != std::string::npos &&
        os.str().find("InflatedAtOnce: 0") != std::string::npos,
      "PrintSelf");
  }

  if (check.Failures)
  {
    std::cerr << check.Failures << " check(s) failed\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
