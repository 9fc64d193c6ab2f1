// The lattice filter: output arrays and frame, VTK's own orientation and angle measures,
// error paths, abort and PrintSelf.
#include "CBC3DTestUtilities.h"
#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DBCCLattice.h"
#include "vtkCBC3DMeshQuality.h"

#include "cbc3d/base/TetTopology.h"

#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkMeshQuality.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkTetra.h>
#include <vtkUnsignedShortArray.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <iostream>
#include <sstream>
#include <string>

namespace
{
// A ball of radius 6 mm in a 20^3 image with the given array type; the label is decided in
// world space.
template <typename ArrayT>
vtkSmartPointer<vtkImageData> MakeBall(double label, const double direction[9])
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(20, 20, 20);
  image->SetSpacing(0.8, 1.0, 1.2);
  image->SetOrigin(5, -7, 30);
  image->SetDirectionMatrix(direction);
  vtkNew<ArrayT> labels;
  labels->SetName("Labels");
  labels->SetNumberOfTuples(image->GetNumberOfPoints());
  double centre[3];
  image->TransformContinuousIndexToPhysicalPoint(9.5, 9.5, 9.5, centre);
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    double p[3];
    image->GetPoint(i, p);
    const double d = std::sqrt(vtkMath::Distance2BetweenPoints(p, centre));
    labels->SetTuple1(i, d <= 6.0 ? label : 0.0);
  }
  image->GetPointData()->SetScalars(labels);
  return image;
}

const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
// A rotation about z by 30 degrees with the y axis flipped: determinant -1.
const double reflection[9] = { 0.8660254037844387, 0.5, 0, 0.5, -0.8660254037844387, 0, 0, 0, 1 };

std::string RunExpectingError(vtkImageData* image, double edge = 0.0)
{
  vtkNew<vtkCBC3DBCCLattice> lattice;
  vtkNew<cbc3dtest::MessageCatcher> catcher;
  lattice->AddObserver(vtkCommand::ErrorEvent, catcher);
  lattice->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, catcher);
  lattice->SetInputData(image);
  lattice->SetEdgeLength(edge);
  lattice->Update();
  CHECK(lattice->GetOutput()->GetNumberOfCells() == 0);
  return catcher->Text;
}

void TestLatticeOnReflectedBall()
{
  vtkSmartPointer<vtkImageData> image = MakeBall<vtkUnsignedShortArray>(128, reflection);
  vtkNew<vtkCBC3DBCCLattice> lattice;
  lattice->SetInputData(image);
  lattice->SetEdgeLength(2.0);
  vtkNew<vtkCBC3DMeshQuality> quality;
  quality->SetInputConnection(lattice->GetOutputPort());
  quality->Update();
  vtkUnstructuredGrid* mesh = quality->GetOutput();
  CHECK(mesh->GetNumberOfCells() > 100);

  auto* labels = vtkIntArray::SafeDownCast(mesh->GetCellData()->GetArray(vtkCBC3DArrayNames::Label));
  CHECK(labels != nullptr);
  if (labels)
  {
    double range[2];
    labels->GetRange(range);
    CHECK(range[0] == 128 && range[1] == 128);
  }

  // VTK's own signed volume: positive for every tet, even with a reflected direction.
  vtkIdType negative = 0;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    CHECK(mesh->GetCellType(c) == VTK_TETRA);
    double p[4][3];
    for (int v = 0; v < 4; ++v)
    {
      mesh->GetPoint(mesh->GetCell(c)->GetPointId(v), p[v]);
    }
    negative += vtkTetra::ComputeVolume(p[0], p[1], p[2], p[3]) > 0 ? 0 : 1;
  }
  CHECK(negative == 0);

  // VTK's minimum dihedral angle agrees: every BCC tet has 60 degrees as its smallest.
  vtkNew<vtkMeshQuality> verdict;
  verdict->SetInputData(lattice->GetOutput());
  verdict->SetTetQualityMeasureToMinAngle();
  verdict->Update();
  vtkDataArray* minAngle = verdict->GetOutput()->GetCellData()->GetArray("Quality");
  CHECK(minAngle != nullptr);
  if (minAngle)
  {
    double range[2];
    minAngle->GetRange(range);
    CHECK(std::abs(range[0] - 60.0) < 1e-6 && std::abs(range[1] - 60.0) < 1e-6);
  }

  // Quality filter figures: 60 and 90 degrees, tissue 128 only, no inverted tet.
  vtkFieldData* fields = mesh->GetFieldData();
  CHECK(fields->GetArray(vtkCBC3DArrayNames::TetCount)->GetTuple1(0) == mesh->GetNumberOfCells());
  CHECK(std::abs(fields->GetArray(vtkCBC3DArrayNames::MinDihedralAngle)->GetTuple1(0) - 60) < 1e-6);
  CHECK(std::abs(fields->GetArray(vtkCBC3DArrayNames::MaxDihedralAngle)->GetTuple1(0) - 90) < 1e-6);
  CHECK(fields->GetArray(vtkCBC3DArrayNames::InvertedTetCount)->GetTuple1(0) == 0);
  CHECK(fields->GetArray(vtkCBC3DArrayNames::TissueLabel)->GetNumberOfTuples() == 1);
  CHECK(fields->GetArray(vtkCBC3DArrayNames::TissueLabel)->GetTuple1(0) == 128);
  CHECK(fields->GetArray(vtkCBC3DArrayNames::LatticeEdgeLength)->GetTuple1(0) == 2.0);
  auto* perTetMax = mesh->GetCellData()->GetArray(vtkCBC3DArrayNames::MaxDihedralAngle);
  CHECK(perTetMax && std::abs(perTetMax->GetRange()[1] - 90.0) < 1e-6);

  // The mesh lies where the image is: its bounds overlap the image's world bounds.
  double meshBounds[6], imageBounds[6];
  mesh->GetBounds(meshBounds);
  image->GetBounds(imageBounds);
  for (int a = 0; a < 3; ++a)
  {
    CHECK(meshBounds[2 * a] < imageBounds[2 * a + 1] && meshBounds[2 * a + 1] > imageBounds[2 * a]);
  }

  std::ostringstream printed;
  lattice->Print(printed);
  CHECK(printed.str().find("EdgeLength: 2") != std::string::npos);
  CHECK(printed.str().find("BackgroundLabels: 0") != std::string::npos);
}

void TestTopologyMatchesVTK()
{
  vtkNew<vtkTetra> tetra;
  for (int e = 0; e < 6; ++e)
  {
    const vtkIdType* ids = tetra->GetEdgeArray(e);
    CHECK(ids[0] == cbc3d::TetEdges[e][0] && ids[1] == cbc3d::TetEdges[e][1]);
  }
  for (int f = 0; f < 4; ++f)
  {
    const vtkIdType* ids = tetra->GetFaceArray(f);
    CHECK(ids[0] == cbc3d::TetFaces[f][0] && ids[1] == cbc3d::TetFaces[f][1] &&
      ids[2] == cbc3d::TetFaces[f][2]);
  }
}

void TestInputs()
{
  // Float labels with whole values are accepted; the default edge is 8 x 0.8 mm.
  {
    vtkNew<vtkCBC3DBCCLattice> lattice;
    lattice->SetInputData(MakeBall<vtkFloatArray>(3, identity));
    lattice->Update();
    CHECK(lattice->GetOutput()->GetNumberOfCells() > 0);
    CHECK(std::abs(lattice->GetOutput()->GetFieldData()->GetArray("LatticeEdgeLength")->GetTuple1(0) - 6.4) < 1e-12);
  }
  // A background list that makes label 3 background leaves no tissue.
  {
    vtkNew<vtkCBC3DBCCLattice> lattice;
    vtkNew<cbc3dtest::MessageCatcher> catcher;
    lattice->AddObserver(vtkCommand::ErrorEvent, catcher);
    lattice->SetInputData(MakeBall<vtkIntArray>(3, identity));
    lattice->SetBackgroundLabel(3);
    lattice->AddBackgroundLabel(0);
    CHECK(lattice->GetNumberOfBackgroundLabels() == 2);
    lattice->Update();
    CHECK(catcher->Text.find("no tissue") != std::string::npos);
  }
  CHECK(RunExpectingError(MakeBall<vtkFloatArray>(2.5, identity)).find("non-integral") != std::string::npos);
  CHECK(RunExpectingError(MakeBall<vtkIntArray>(1, identity), -2.0).find("positive") != std::string::npos);
  CHECK(RunExpectingError(MakeBall<vtkIntArray>(1, identity), 1e-5).find("memory") != std::string::npos);
  {
    vtkSmartPointer<vtkImageData> image = MakeBall<vtkIntArray>(1, identity);
    vtkNew<vtkDoubleArray> vectors;
    vectors->SetName("Vectors");
    vectors->SetNumberOfComponents(2);
    vectors->SetNumberOfTuples(image->GetNumberOfPoints());
    vectors->Fill(1.0);
    image->GetPointData()->SetScalars(vectors);
    CHECK(RunExpectingError(image).find("components") != std::string::npos);
    // A chosen array that is missing is an error, never a silent switch to another array.
    image->GetPointData()->SetScalars(MakeBall<vtkIntArray>(1, identity)->GetPointData()->GetScalars());
    {
      vtkNew<vtkCBC3DBCCLattice> lattice;
      vtkNew<cbc3dtest::MessageCatcher> catcher;
      lattice->AddObserver(vtkCommand::ErrorEvent, catcher);
      lattice->SetInputData(image);
      lattice->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Nope");
      lattice->Update();
      CHECK(catcher->Text.find("no label array") != std::string::npos);
      CHECK(catcher->Text.find("Labels") != std::string::npos); // lists what is there
    }
    image->GetPointData()->Initialize();
    CHECK(RunExpectingError(image).find("no label array") != std::string::npos);
  }
  {
    vtkNew<vtkImageData> slice;
    slice->SetDimensions(10, 10, 1);
    slice->AllocateScalars(VTK_INT, 1);
    static_cast<vtkIntArray*>(slice->GetPointData()->GetScalars())->Fill(1);
    CHECK(RunExpectingError(slice).find("3-D") != std::string::npos);
  }
}

void TestAbort()
{
  vtkNew<vtkCBC3DBCCLattice> lattice;
  lattice->SetInputData(MakeBall<vtkIntArray>(1, identity));
  lattice->SetEdgeLength(0.5);
  vtkNew<vtkCallbackCommand> stop;
  stop->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  lattice->AddObserver(vtkCommand::ProgressEvent, stop);
  lattice->Update();
  CHECK(lattice->GetOutput()->GetNumberOfCells() == 0);
}
} // namespace

// Stages share one conversion of the label image (vtkCBC3DLabelImageCache): a change to the
// labels, to the image's geometry or to the background labels must be seen, never a stale copy.
void TestSharedImageFollowsChanges()
{
  vtkSmartPointer<vtkImageData> image = MakeBall<vtkUnsignedShortArray>(128, identity);
  vtkNew<vtkCBC3DBCCLattice> lattice;
  lattice->SetInputData(image);
  lattice->SetEdgeLength(2.0);
  lattice->Update();
  const vtkIdType ball = lattice->GetOutput()->GetNumberOfCells();
  CHECK(ball > 0);
  vtkNew<vtkCBC3DBCCLattice> other; // a second stage on the same image gets the same lattice
  other->SetInputData(image);
  other->SetEdgeLength(2.0);
  other->Update();
  CHECK(other->GetOutput()->GetNumberOfCells() == ball);

  // Half the ball becomes background: the lattice covers a smaller box.
  vtkDataArray* labels = image->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    double p[3];
    image->GetPoint(i, p);
    if (p[0] < 5.0 + 0.8 * 9.5)
    {
      labels->SetTuple1(i, 0.0);
    }
  }
  labels->Modified();
  other->Modified();
  other->Update();
  const vtkIdType half = other->GetOutput()->GetNumberOfCells();
  CHECK(half > 0 && half < ball);

  // The tissue label made background: no tissue left, an error and no tets.
  other->AddBackgroundLabel(128);
  vtkNew<cbc3dtest::MessageCatcher> catcher;
  other->AddObserver(vtkCommand::ErrorEvent, catcher);
  other->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, catcher);
  other->Update();
  CHECK(other->GetOutput()->GetNumberOfCells() == 0);
  CHECK(catcher->Text.find("no tissue") != std::string::npos);

  // Twice the spacing along x with the labels as they were: a box twice as wide.
  other->SetBackgroundLabel(0);
  image->SetSpacing(1.6, 1.0, 1.2);
  other->Update();
  CHECK(other->GetOutput()->GetNumberOfCells() > half);
}

int TestCBC3DBCCLattice(int, char*[])
{
  TestLatticeOnReflectedBall();
  TestTopologyMatchesVTK();
  TestInputs();
  TestAbort();
  TestSharedImageFollowsChanges();
  return cbc3dtest::Finish();
}
