// A program outside the cbc3d source tree, built against an installed CBC3D: a two-tissue
// ball made in memory, meshed with vtkCBC3DBCCLattice, measured with vtkCBC3DMeshQuality.
// Exit 0 when the BCC angles (60 and 90 degrees) and both label values come out, 1 otherwise.
#include <vtkCBC3DArrayNames.h>
#include <vtkCBC3DBCCLattice.h>
#include <vtkCBC3DMeshQuality.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkShortArray.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <iostream>
#include <set>

namespace
{
double Field(vtkUnstructuredGrid* mesh, const char* name)
{
  vtkDataArray* array = mesh->GetFieldData()->GetArray(name);
  return array && array->GetNumberOfTuples() > 0 ? array->GetTuple1(0) : std::nan("");
}
}

int main()
{
  // 40^3 voxels of 0.5 mm: a ball of radius 8 mm, label 7 inside radius 4 mm, 300 around it.
  const int n = 40;
  vtkNew<vtkImageData> image;
  image->SetDimensions(n, n, n);
  image->SetSpacing(0.5, 0.5, 0.5);
  image->SetOrigin(-10.0, -10.0, -10.0);
  vtkNew<vtkShortArray> labels;
  labels->SetName("labels");
  labels->SetNumberOfValues(static_cast<vtkIdType>(n) * n * n);
  vtkIdType id = 0;
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i, ++id)
      {
        const double x = -10.0 + 0.5 * i, y = -10.0 + 0.5 * j, z = -10.0 + 0.5 * k;
        const double r = std::sqrt(x * x + y * y + z * z);
        labels->SetValue(id, r <= 4.0 ? 7 : (r <= 8.0 ? 300 : 0));
      }
    }
  }
  image->GetPointData()->SetScalars(labels);

  vtkNew<vtkCBC3DBCCLattice> lattice;
  lattice->SetInputData(image);
  lattice->SetEdgeLength(2.0);
  vtkNew<vtkCBC3DMeshQuality> quality;
  quality->SetInputConnection(lattice->GetOutputPort());
  quality->SetImageData(image);
  quality->Update();
  vtkUnstructuredGrid* mesh = quality->GetOutput();

  int failures = 0;
  const vtkIdType tets = mesh->GetNumberOfCells();
  const double minAngle = Field(mesh, vtkCBC3DArrayNames::MinDihedralAngle);
  const double maxAngle = Field(mesh, vtkCBC3DArrayNames::MaxDihedralAngle);
  const double hausdorff = Field(mesh, "HausdorffDistance");
  std::cout << "tets " << tets << ", points " << mesh->GetNumberOfPoints() << ", dihedral "
            << minAngle << " to " << maxAngle << " degrees, Hausdorff " << hausdorff << " mm\n";
  if (tets < 1000)
  {
    std::cerr << "too few tets: " << tets << "\n";
    ++failures;
  }
  if (!(std::abs(minAngle - 60.0) < 1e-6 && std::abs(maxAngle - 90.0) < 1e-6))
  {
    std::cerr << "dihedral angles are not 60 and 90 degrees\n";
    ++failures;
  }
  if (!(hausdorff >= 0.0 && hausdorff < 4.0))
  {
    std::cerr << "implausible Hausdorff distance: " << hausdorff << "\n";
    ++failures;
  }
  std::set<int> found;
  if (vtkDataArray* label = mesh->GetCellData()->GetArray(vtkCBC3DArrayNames::Label))
  {
    for (vtkIdType c = 0; c < label->GetNumberOfTuples(); ++c)
    {
      found.insert(static_cast<int>(label->GetTuple1(c)));
    }
  }
  if (found != std::set<int>{ 7, 300 })
  {
    std::cerr << "Label values are not {7, 300}:";
    for (int value : found)
    {
      std::cerr << " " << value;
    }
    std::cerr << "\n";
    ++failures;
  }
  std::cout << (failures ? "FAILED" : "OK") << "\n";
  return failures ? 1 : 0;
}
