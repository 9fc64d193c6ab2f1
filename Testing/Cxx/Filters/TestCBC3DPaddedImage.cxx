// Cost follows the tissues, not the voxels: the conversion stores only the box of the voxels
// that are not the first background label (and one voxel around it), and an image padded with
// background on its high side meshes to the same bytes as the unpadded one.
#include "CBC3DTestUtilities.h"
#include "vtkCBC3DConvert.h"
#include "vtkCBC3DMesher.h"

#include "cbc3d/base/LabelImage.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <string>

namespace
{
// Nested shells off the image's centre (a ball of label 3 in a shell of label 5) in voxels of
// 0.9 x 1 x 1.1 mm, in an image of n x m x p voxels: the first 26^3 hold the shells, the rest is
// `padding`.
vtkSmartPointer<vtkImageData> Shells(int n, int m, int p, int padding = 0)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, m, p);
  image->SetSpacing(0.9, 1.0, 1.1);
  image->SetOrigin(-4.0, 2.0, 7.5);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  vtkDataArray* labels = image->GetPointData()->GetScalars();
  for (int k = 0; k < p; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double r = std::sqrt((i - 12.0) * (i - 12.0) + (j - 11.5) * (j - 11.5) + (k - 13.0) * (k - 13.0));
        const bool inside = i < 26 && j < 26 && k < 26;
        labels->SetTuple1(i + vtkIdType(n) * (j + vtkIdType(m) * k),
          !inside ? padding : r <= 5.0 ? 3 : r <= 10.0 ? 5 : 0);
      }
  return image;
}

vtkSmartPointer<vtkUnstructuredGrid> Mesh(vtkImageData* image, int threads, bool paper)
{
  vtkNew<vtkCBC3DMesher> mesher;
  mesher->SetInputData(image);
  mesher->SetNumberOfThreads(threads);
  if (paper)
  {
    mesher->SetEdgeLength(8.0);
    mesher->SetFidelity(0.95);
  }
  mesher->Update();
  auto mesh = vtkSmartPointer<vtkUnstructuredGrid>::New();
  mesh->ShallowCopy(mesher->GetOutput());
  return mesh;
}

// The same points bit for bit, the same tets and labels.
bool SameMesh(vtkUnstructuredGrid* a, vtkUnstructuredGrid* b)
{
  if (a->GetNumberOfPoints() != b->GetNumberOfPoints() || a->GetNumberOfCells() != b->GetNumberOfCells() ||
    a->GetNumberOfCells() == 0)
    return false;
  for (vtkIdType p = 0; p < a->GetNumberOfPoints(); ++p)
  {
    double x[3], y[3];
    a->GetPoint(p, x);
    b->GetPoint(p, y);
    if (x[0] != y[0] || x[1] != y[1] || x[2] != y[2])
      return false;
  }
  vtkDataArray* la = a->GetCellData()->GetArray("Label");
  vtkDataArray* lb = b->GetCellData()->GetArray("Label");
  if (!la || !lb)
    return false;
  vtkNew<vtkIdList> pa, pb;
  for (vtkIdType c = 0; c < a->GetNumberOfCells(); ++c)
  {
    a->GetCellPoints(c, pa);
    b->GetCellPoints(c, pb);
    if (la->GetTuple1(c) != lb->GetTuple1(c) || pa->GetNumberOfIds() != pb->GetNumberOfIds())
      return false;
    for (vtkIdType v = 0; v < pa->GetNumberOfIds(); ++v)
      if (pa->GetId(v) != pb->GetId(v))
        return false;
  }
  return true;
}

// The conversion stores the box of the voxels other than the first background label, one voxel
// around it, and reads every voxel's label as the image holds it.
void TestStoredBox()
{
  // Padding of a second background label: the box must reach it, since beyond the box every
  // voxel is taken for the first background label.
  for (const bool secondBackground : { false, true })
  {
    vtkSmartPointer<vtkImageData> image = Shells(40, 34, 30, secondBackground ? 7 : 0);
    std::vector<vtkTypeInt64> backgrounds = { 0 };
    if (secondBackground)
    {
      backgrounds.push_back(7);
    }
    cbc3d::LabelImage out;
    std::string error;
    CHECK(vtkCBC3DConvert::ToLabelImage(image, image->GetPointData()->GetScalars(), backgrounds, out, error));
    CHECK(error.empty());
    // Shells of radius 10 about (12, 11.5, 13): voxels 3..21, 2..21 and 4..22 (j is half a
    // voxel off the centre), and one around.
    const std::array<int, 3> lower = { 2, 1, 3 };
    const std::array<int, 3> size = { 21, 22, 21 };
    CHECK(secondBackground || (out.StoredLower == lower && out.StoredSize == size));
    // The padding of label 7 runs from the image's low faces to its high faces.
    CHECK(!secondBackground ||
      (out.StoredLower == (std::array<int, 3>{ 0, 0, 0 }) && out.StoredSize == (std::array<int, 3>{ 40, 34, 30 })));
    vtkDataArray* labels = image->GetPointData()->GetScalars();
    for (int k = 0; k < 30; ++k)
      for (int j = 0; j < 34; ++j)
        for (int i = 0; i < 40; ++i)
        {
          const vtkIdType voxel = i + 40 * (j + vtkIdType(34) * k);
          if (out.Codes.ValueOf(out.LabelOf(i, j, k)) != std::int64_t(labels->GetTuple1(voxel)))
          {
            CHECK(false);
            return;
          }
        }
  }
}

// Padding on the high side leaves the world frame as it is: the same mesh, byte for byte, at
// one and two threads, at the mesher's defaults and at the paper's settings.
void TestPaddedMeshesTheSame()
{
  for (const bool paper : { false, true })
  {
    const auto plain = Mesh(Shells(26, 26, 26), 1, paper);
    CHECK(plain->GetNumberOfCells() > 100);
    CHECK(SameMesh(plain, Mesh(Shells(41, 30, 52), 1, paper)));
    CHECK(SameMesh(plain, Mesh(Shells(41, 30, 52), 2, paper)));
  }
}
} // namespace

int TestCBC3DPaddedImage(int, char*[])
{
  TestStoredBox();
  TestPaddedMeshesTheSame();
  return cbc3dtest::Finish();
}
