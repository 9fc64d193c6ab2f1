// The deformation filter: moved points and Displacement, field data, error paths, PrintSelf.
#include "CBC3DTestUtilities.h"
#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DBCCLattice.h"
#include "vtkCBC3DDeformation.h"

#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <iostream>
#include <sstream>
#include <string>

int TestCBC3DDeformation(int, char*[])
{
  // A ball of label 2, radius 7 mm, in 1 mm voxels.
  vtkNew<vtkImageData> image;
  image->SetDimensions(24, 24, 24);
  image->SetOrigin(4, -2, 9);
  image->AllocateScalars(VTK_SHORT, 1);
  vtkDataArray* labels = image->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    int ijk[3] = { int(i % 24), int((i / 24) % 24), int(i / 576) };
    const double r = std::sqrt(std::pow(ijk[0] - 11.5, 2) + std::pow(ijk[1] - 11.5, 2) + std::pow(ijk[2] - 11.5, 2));
    labels->SetTuple1(i, r <= 7.0 ? 2 : 0);
  }
  vtkNew<vtkCBC3DBCCLattice> lattice;
  lattice->SetInputData(image);
  lattice->SetEdgeLength(4.0);
  vtkNew<vtkCBC3DDeformation> deformation;
  deformation->SetInputConnection(lattice->GetOutputPort());
  deformation->SetImageData(image);
  deformation->SetPatternToFace();
  deformation->SetIterations(3);
  deformation->Update();
  vtkUnstructuredGrid* moved = deformation->GetOutput();
  vtkUnstructuredGrid* start = lattice->GetOutput();
  CHECK(moved->GetNumberOfCells() == start->GetNumberOfCells());
  vtkDataArray* displacement = moved->GetPointData()->GetArray(vtkCBC3DArrayNames::Displacement);
  CHECK(displacement && displacement->GetNumberOfComponents() == 3);
  double largest = 0.0, mismatch = 0.0;
  for (vtkIdType p = 0; displacement && p < moved->GetNumberOfPoints(); ++p)
  {
    double a[3], b[3], d[3];
    moved->GetPoint(p, a);
    start->GetPoint(p, b);
    displacement->GetTuple(p, d);
    for (int c = 0; c < 3; ++c)
    {
      mismatch = std::max(mismatch, std::abs(a[c] - b[c] - d[c]));
    }
    largest = std::max(largest, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
  }
  CHECK(largest > 0.1);      // the surface moved
  CHECK(mismatch < 1e-9);    // by exactly the reported displacement
  vtkFieldData* fields = moved->GetFieldData();
  CHECK(fields->GetArray(vtkCBC3DArrayNames::DeformationIterations)->GetTuple1(0) >= 1);
  CHECK(fields->GetArray(vtkCBC3DArrayNames::DeformationSources)->GetTuple1(0) > 0);
  CHECK(fields->GetArray(vtkCBC3DArrayNames::DeformationTargets)->GetTuple1(0) > 0);
  CHECK(vtkStringArray::SafeDownCast(fields->GetAbstractArray(vtkCBC3DArrayNames::DeformationStopReason)) != nullptr);

  std::ostringstream printed;
  deformation->Print(printed);
  CHECK(printed.str().find("Pattern: Face") != std::string::npos);
  CHECK(std::string(deformation->GetPatternAsString()) == "Face");
  CHECK(printed.str().find("TargetPlacement: VoxelFace") != std::string::npos); // the default
  deformation->SetTargetPlacementToVoxelCentre();
  CHECK(std::string(deformation->GetTargetPlacementAsString()) == "VoxelCentre");
  deformation->SetTargetPlacementToVoxelFace();
  CHECK(std::string(deformation->GetTargetPlacementAsString()) == "VoxelFace");
  CHECK(printed.str().find("KeepVolumes: on") != std::string::npos); // the default
  deformation->KeepVolumesOff();
  std::ostringstream printedOff;
  deformation->Print(printedOff);
  CHECK(printedOff.str().find("KeepVolumes: off") != std::string::npos);
  deformation->KeepVolumesOn();

  vtkNew<cbc3dtest::MessageCatcher> errors;
  deformation->AddObserver(vtkCommand::ErrorEvent, errors);
  deformation->SetPoissonRatio(0.5);
  deformation->Update();
  CHECK(errors->Text.find("Poisson") != std::string::npos);
  CHECK(deformation->GetOutput()->GetNumberOfCells() == 0);
  deformation->SetPoissonRatio(0.3);
  deformation->SetTissueYoungModulus(2, -1.0);
  deformation->Update();
  CHECK(errors->Text.find("Young") != std::string::npos);

  return cbc3dtest::Finish();
}
