// The one-shot mesher: every stage's arrays in one output, errors named by stage, and a stop
// request that ends the run early with an empty output.
#include "CBC3DTestUtilities.h"
#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DMesher.h"

#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

namespace
{
// Nested shells: a ball of label 3 inside a shell of label 5, in 1 mm voxels.
vtkSmartPointer<vtkImageData> Shells(int n)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->AllocateScalars(VTK_INT, 1);
  vtkDataArray* labels = image->GetPointData()->GetScalars();
  const double c = (n - 1) / 2.0;
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    double p[3];
    image->GetPoint(i, p);
    const double r = std::sqrt((p[0] - c) * (p[0] - c) + (p[1] - c) * (p[1] - c) + (p[2] - c) * (p[2] - c));
    labels->SetTuple1(i, r <= 0.2 * n ? 3 : r <= 0.4 * n ? 5 : 0);
  }
  return image;
}
} // namespace

int TestCBC3DMesher(int, char*[])
{
  vtkNew<vtkCBC3DMesher> mesher;
  mesher->SetInputData(Shells(30));
  mesher->SetEdgeLength(4.0);
  mesher->Update();
  vtkUnstructuredGrid* mesh = mesher->GetOutput();
  CHECK(mesh->GetNumberOfCells() > 100);
  for (const char* name : { vtkCBC3DArrayNames::Label, vtkCBC3DArrayNames::RefinementLevel,
         vtkCBC3DArrayNames::MinDihedralAngle, vtkCBC3DArrayNames::MaxDihedralAngle })
  {
    CHECK(mesh->GetCellData()->GetArray(name) != nullptr);
  }
  CHECK(mesh->GetPointData()->GetArray(vtkCBC3DArrayNames::Displacement) != nullptr);
  vtkFieldData* fields = mesh->GetFieldData();
  for (const char* name : { vtkCBC3DArrayNames::LatticeEdgeLength, vtkCBC3DArrayNames::FidelityF1,
         vtkCBC3DArrayNames::DeformationIterations, vtkCBC3DArrayNames::HausdorffDistance })
  {
    CHECK(fields->GetArray(name) != nullptr || fields->GetAbstractArray(name) != nullptr);
  }
  CHECK(fields->GetArray(vtkCBC3DArrayNames::InvertedTetCount)->GetTuple1(0) == 0);
  CHECK(fields->GetArray(vtkCBC3DArrayNames::TissueLabel)->GetNumberOfTuples() == 2);

  // Stop when a quarter of the work is done: the run ends early, with an empty output.
  vtkNew<vtkCBC3DMesher> stopped;
  stopped->SetInputData(Shells(60));
  stopped->SetEdgeLength(3.0);
  double furthest = 0.0; // the largest progress reported before the pipeline's closing 1.0
  vtkNew<vtkCallbackCommand> stop;
  stop->SetClientData(&furthest);
  stop->SetCallback([](vtkObject* caller, unsigned long, void* clientData, void*) {
    auto* algorithm = static_cast<vtkAlgorithm*>(caller);
    double& seen = *static_cast<double*>(clientData);
    if (algorithm->GetProgress() < 1.0)
    {
      seen = std::max(seen, algorithm->GetProgress());
    }
    if (algorithm->GetProgress() > 0.25)
    {
      algorithm->SetAbortExecute(1);
    }
  });
  stopped->AddObserver(vtkCommand::ProgressEvent, stop);
  stopped->Update();
  CHECK(stopped->GetOutput()->GetNumberOfCells() == 0);
  CHECK(furthest > 0.25 && furthest < 0.5);

  // An image with no tissue: the error names the stage.
  vtkNew<vtkImageData> empty;
  empty->SetDimensions(5, 5, 5);
  empty->AllocateScalars(VTK_INT, 1);
  empty->GetPointData()->GetScalars()->Fill(0);
  vtkNew<vtkCBC3DMesher> failing;
  vtkNew<cbc3dtest::MessageCatcher> errors;
  failing->AddObserver(vtkCommand::ErrorEvent, errors);
  failing->SetInputData(empty);
  failing->Update();
  CHECK(errors->Text.find("BCC lattice: the image has no tissue") != std::string::npos);

  return cbc3dtest::Finish();
}
