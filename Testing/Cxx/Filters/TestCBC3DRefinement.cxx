// The refinement filter: output arrays, fidelity in field data, error paths and PrintSelf.
#include "CBC3DTestUtilities.h"
#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DBCCLattice.h"
#include "vtkCBC3DRefinement.h"

#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkTetra.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <iostream>
#include <sstream>
#include <string>

namespace
{
// Two boxes of labels 4 and 9 that share a face, in 1 mm voxels.
vtkSmartPointer<vtkImageData> TwoBoxes()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(24, 16, 16);
  image->SetOrigin(-10, 3, 7);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  vtkDataArray* labels = image->GetPointData()->GetScalars();
  for (int k = 0; k < 16; ++k)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 24; ++i)
      {
        const bool inside = i >= 3 && i < 21 && j >= 3 && j < 13 && k >= 4 && k < 12;
        labels->SetTuple1(i + 24 * (j + 16 * k), inside ? (i < 11 ? 4 : 9) : 0);
      }
  return image;
}
} // namespace

int TestCBC3DRefinement(int, char*[])
{
  vtkSmartPointer<vtkImageData> image = TwoBoxes();
  vtkNew<vtkCBC3DBCCLattice> lattice;
  lattice->SetInputData(image);
  lattice->SetEdgeLength(5.0);
  vtkNew<vtkCBC3DRefinement> refinement;
  refinement->SetInputConnection(lattice->GetOutputPort());
  refinement->SetImageData(image);
  refinement->SetFidelity(0.97);
  refinement->Update();
  vtkUnstructuredGrid* mesh = refinement->GetOutput();
  lattice->Update();
  CHECK(mesh->GetNumberOfCells() > lattice->GetOutput()->GetNumberOfCells());

  auto* levels = vtkUnsignedCharArray::SafeDownCast(
    mesh->GetCellData()->GetArray(vtkCBC3DArrayNames::RefinementLevel));
  CHECK(levels && levels->GetNumberOfTuples() == mesh->GetNumberOfCells());
  CHECK(levels && levels->GetRange()[1] >= 1);
  vtkDataArray* labels = mesh->GetCellData()->GetArray(vtkCBC3DArrayNames::Label);
  CHECK(labels && labels->GetRange()[0] == 4 && labels->GetRange()[1] == 9);
  vtkIdType negative = 0;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    double p[4][3];
    for (int v = 0; v < 4; ++v)
      mesh->GetPoint(mesh->GetCell(c)->GetPointId(v), p[v]);
    negative += vtkTetra::ComputeVolume(p[0], p[1], p[2], p[3]) > 0 ? 0 : 1;
  }
  CHECK(negative == 0);

  vtkFieldData* fields = mesh->GetFieldData();
  vtkDataArray* tissue = fields->GetArray(vtkCBC3DArrayNames::FidelityLabel);
  vtkDataArray* f1 = fields->GetArray(vtkCBC3DArrayNames::FidelityF1);
  vtkDataArray* f2 = fields->GetArray(vtkCBC3DArrayNames::FidelityF2);
  CHECK(tissue && tissue->GetNumberOfTuples() == 2 && tissue->GetTuple1(0) == 4 && tissue->GetTuple1(1) == 9);
  CHECK(f1 && f2);
  auto* reason = vtkStringArray::SafeDownCast(fields->GetAbstractArray(vtkCBC3DArrayNames::RefinementStopReason));
  CHECK(reason && reason->GetNumberOfValues() == 1);
  if (f1 && f2 && reason && reason->GetValue(0) == "every tissue reached the fidelity target")
  {
    CHECK(f1->GetRange()[0] >= 0.97 && f2->GetRange()[0] >= 0.97);
  }
  CHECK(fields->GetArray(vtkCBC3DArrayNames::LatticeEdgeLength) != nullptr); // passed through
  CHECK(fields->GetArray(vtkCBC3DArrayNames::FidelityComponents)->GetTuple1(0) == 1);
  CHECK(fields->GetArray(vtkCBC3DArrayNames::FidelityComponentsInMesh)->GetTuple1(1) == 1);

  std::ostringstream printed;
  refinement->Print(printed);
  CHECK(printed.str().find("Fidelity: 0.97") != std::string::npos);
  CHECK(printed.str().find("MinimumEdgeLength: 0 mm (the voxel size)") != std::string::npos);

  // A fidelity out of range and a mesh without labels are errors with an empty output.
  {
    vtkNew<cbc3dtest::MessageCatcher> errors;
    refinement->AddObserver(vtkCommand::ErrorEvent, errors);
    refinement->SetFidelity(1.5);
    refinement->Update();
    CHECK(errors->Text.find("fidelity") != std::string::npos);
    CHECK(refinement->GetOutput()->GetNumberOfCells() == 0);
  }
  {
    vtkNew<vtkUnstructuredGrid> unlabelled;
    unlabelled->DeepCopy(lattice->GetOutput());
    unlabelled->GetCellData()->RemoveArray(vtkCBC3DArrayNames::Label);
    vtkNew<vtkCBC3DRefinement> other;
    vtkNew<cbc3dtest::MessageCatcher> errors;
    other->AddObserver(vtkCommand::ErrorEvent, errors);
    other->SetInputData(unlabelled);
    other->SetImageData(image);
    other->Update();
    CHECK(errors->Text.find("Label") != std::string::npos);
  }
  return cbc3dtest::Finish();
}
