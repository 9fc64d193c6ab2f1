// The quality filter against known answers: angles of a regular tet, a BCC tet and a sliver;
// the Hausdorff distance, volume and topology of a voxel block meshed at its voxel corners; a
// lost tissue; the topology of hinged tets.
#include "CBC3DTestUtilities.h"
#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DMeshQuality.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
bool Near(double a, double b, double tolerance = 1e-9)
{
  return std::abs(a - b) <= tolerance;
}

vtkSmartPointer<vtkUnstructuredGrid> MakeMesh(const std::vector<std::array<double, 3>>& points,
  const std::vector<std::array<vtkIdType, 4>>& tets, const std::vector<int>& labels)
{
  auto mesh = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (const auto& p : points)
  {
    pts->InsertNextPoint(p.data());
  }
  mesh->SetPoints(pts);
  mesh->Allocate(static_cast<vtkIdType>(tets.size()));
  vtkNew<vtkIntArray> label;
  label->SetName(vtkCBC3DArrayNames::Label);
  for (std::size_t t = 0; t < tets.size(); ++t)
  {
    mesh->InsertNextCell(VTK_TETRA, 4, tets[t].data());
    label->InsertNextValue(labels[t]);
  }
  mesh->GetCellData()->AddArray(label);
  return mesh;
}

double Field(vtkUnstructuredGrid* mesh, const char* name, vtkIdType i = 0)
{
  vtkDataArray* array = mesh->GetFieldData()->GetArray(name);
  return array && i < array->GetNumberOfTuples() ? array->GetTuple1(i) : -12345.0;
}

void TestAngles()
{
  const double a = vtkMath::RadiansFromDegrees(3.0);
  // Regular tet; BCC tet; a tet whose dihedral angle at edge 0-2 is 3 degrees.
  auto mesh = MakeMesh({ { 1, 1, 1 }, { 1, -1, -1 }, { -1, 1, -1 }, { -1, -1, 1 },
                         { 10.5, 0.5, 0.5 }, { 11.5, 0.5, 0.5 }, { 11, 0, 0 }, { 11, 1, 0 },
                         { 20, 0, 0 }, { 20.5, 1, 0 }, { 21, 0, 0 }, { 20.5, std::cos(a), std::sin(a) } },
    { { 0, 1, 2, 3 }, { 4, 5, 6, 7 }, { 8, 9, 10, 11 } }, { 1, 2, 3 });
  vtkNew<vtkCBC3DMeshQuality> quality;
  quality->SetInputData(mesh);
  quality->Update();
  vtkUnstructuredGrid* out = quality->GetOutput();
  vtkDataArray* minAngle = out->GetCellData()->GetArray(vtkCBC3DArrayNames::MinDihedralAngle);
  vtkDataArray* maxAngle = out->GetCellData()->GetArray(vtkCBC3DArrayNames::MaxDihedralAngle);
  CHECK(minAngle && maxAngle);
  if (!minAngle || !maxAngle)
  {
    return;
  }
  const double regular = vtkMath::DegreesFromRadians(std::acos(1.0 / 3.0));
  CHECK(Near(minAngle->GetTuple1(0), regular) && Near(maxAngle->GetTuple1(0), regular));
  CHECK(Near(regular, 70.5288, 1e-4));
  CHECK(Near(minAngle->GetTuple1(1), 60.0) && Near(maxAngle->GetTuple1(1), 90.0));
  CHECK(Near(minAngle->GetTuple1(2), 3.0)); // vtkMeshQuality's MinAngle says 89.3 here
  CHECK(Field(out, vtkCBC3DArrayNames::TetCount) == 3);
  CHECK(Field(out, vtkCBC3DArrayNames::SmallAngleTetCount) == 1);
  CHECK(Field(out, vtkCBC3DArrayNames::LargeAngleTetCount) == 0);
  CHECK(Near(Field(out, vtkCBC3DArrayNames::MinDihedralAngle), 3.0));
  CHECK(Field(out, vtkCBC3DArrayNames::TissueLabel, 2) == 3);
  CHECK(Field(out, vtkCBC3DArrayNames::TissueSmallAngleTetCount, 2) == 1);
  CHECK(Near(Field(out, vtkCBC3DArrayNames::TissueMaxDihedralAngle, 1), 90.0));
  // Without an image there are no distances.
  CHECK(out->GetFieldData()->GetArray(vtkCBC3DArrayNames::HausdorffDistance) == nullptr);
}

// A 2x2x2 block of label 5 in a 4x4x4 image, meshed as the cube through the outer voxel
// corners (six tets around its diagonal). Every corner is half a voxel diagonal from the
// nearest block voxel centre, and every block voxel is a boundary voxel whose nearest corner is
// just as far: the Hausdorff distance is 0.5 * |spacing| both ways.
void TestBlockHausdorff()
{
  const double spacing[3] = { 0.5, 1.0, 2.0 };
  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 4, 4);
  image->SetSpacing(spacing);
  image->SetOrigin(-3, 7, 11);
  image->AllocateScalars(VTK_SHORT, 1);
  auto* labels = image->GetPointData()->GetScalars();
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
      {
        const bool block = i >= 1 && i <= 2 && j >= 1 && j <= 2 && k >= 1 && k <= 2;
        labels->SetTuple1(i + 4 * (j + 4 * k), block ? 5 : 0);
      }
  std::vector<std::array<double, 3>> corners;
  for (int c = 0; c < 8; ++c)
  {
    double ijk[3] = { c & 1 ? 2.5 : 0.5, c & 2 ? 2.5 : 0.5, c & 4 ? 2.5 : 0.5 };
    std::array<double, 3> world;
    image->TransformContinuousIndexToPhysicalPoint(ijk, world.data());
    corners.push_back(world);
  }
  // The six tets of the cube around the diagonal 0-7 (corner c has bits x=1, y=2, z=4).
  auto mesh = MakeMesh(corners,
    { { 0, 1, 3, 7 }, { 0, 3, 2, 7 }, { 0, 2, 6, 7 }, { 0, 6, 4, 7 }, { 0, 4, 5, 7 }, { 0, 5, 1, 7 } },
    { 5, 5, 5, 5, 5, 5 });
  vtkNew<vtkCBC3DMeshQuality> quality;
  quality->SetInputData(mesh);
  quality->SetImageData(image);
  quality->Update();
  vtkUnstructuredGrid* out = quality->GetOutput();
  const double expected =
    0.5 * std::sqrt(spacing[0] * spacing[0] + spacing[1] * spacing[1] + spacing[2] * spacing[2]);
  CHECK(Near(Field(out, vtkCBC3DArrayNames::HausdorffDistance), expected, 1e-12));
  CHECK(Near(Field(out, vtkCBC3DArrayNames::TissueMeshToImageDistance), expected, 1e-12));
  CHECK(Near(Field(out, vtkCBC3DArrayNames::TissueImageToMeshDistance), expected, 1e-12));
  CHECK(Near(Field(out, vtkCBC3DArrayNames::HausdorffDistance95), expected, 1e-12));
  CHECK(Near(Field(out, vtkCBC3DArrayNames::MeanSurfaceDistance), expected, 1e-12));
  CHECK(Field(out, vtkCBC3DArrayNames::InvertedTetCount) == 0);
  // Volumes: the mesh is voxel-exact, the block's eight voxels of 0.5 x 1 x 2 mm.
  CHECK(Near(Field(out, vtkCBC3DArrayNames::TissueVolume), 8.0, 1e-12));
  CHECK(Near(Field(out, vtkCBC3DArrayNames::TissueImageVolume), 8.0, 1e-12));
  // Topology: a ball in the mesh and in the image.
  namespace names = vtkCBC3DArrayNames;
  CHECK(Field(out, names::FaceComponents) == 1 && Field(out, names::VertexComponents) == 1);
  CHECK(Field(out, names::HingedParts) == 0 && Field(out, names::NonManifoldEdges) == 0 &&
    Field(out, names::NonManifoldVertices) == 0);
  CHECK(Field(out, names::SurfaceEuler) == 2 && Field(out, names::ImageSurfaceEuler) == 2);
  CHECK(Field(out, names::SolverReady) == 1);
  CHECK(Field(out, names::TissueSurfaceEuler) == 2 && Field(out, names::TissueImageSurfaceEuler) == 2);
  CHECK(out->GetFieldData()->GetArray(names::SolverReady)->IsA("vtkIdTypeArray"));

  // Shift the mesh by 0.1 mm along x: the corners on the +x side are then farther.
  vtkPoints* points = mesh->GetPoints();
  for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p)
  {
    double x[3];
    points->GetPoint(p, x);
    x[0] += 0.1;
    points->SetPoint(p, x);
  }
  mesh->Modified();
  quality->Update();
  const double shifted = std::sqrt(0.35 * 0.35 + 0.5 * 0.5 + 1.0 * 1.0);
  CHECK(Near(Field(quality->GetOutput(), vtkCBC3DArrayNames::HausdorffDistance), shifted, 1e-12));

  // A second tissue in the image that the mesh lost: NaN for it and for the mesh, a warning.
  labels->SetTuple1(0, 7);
  image->Modified();
  vtkNew<cbc3dtest::MessageCatcher> warnings;
  quality->AddObserver(vtkCommand::WarningEvent, warnings);
  quality->Update();
  out = quality->GetOutput();
  CHECK(Field(out, vtkCBC3DArrayNames::TissueLabel, 1) == 7);
  CHECK(Field(out, vtkCBC3DArrayNames::TissueTetCount, 1) == 0);
  CHECK(std::isnan(Field(out, vtkCBC3DArrayNames::TissueHausdorffDistance, 1)));
  CHECK(std::isnan(Field(out, vtkCBC3DArrayNames::HausdorffDistance)));
  CHECK(Near(Field(out, vtkCBC3DArrayNames::TissueHausdorffDistance, 0), shifted, 1e-12));
  CHECK(Field(out, vtkCBC3DArrayNames::TissueVolume, 1) == 0.0);
  CHECK(Near(Field(out, vtkCBC3DArrayNames::TissueImageVolume, 1), 1.0, 1e-12));
  CHECK(warnings->Text.find("tissue 7 is in the image but not in the mesh") != std::string::npos);
  // The lost voxel touches the block at a corner: two spheres glued at a point in the image.
  CHECK(Field(out, vtkCBC3DArrayNames::ImageSurfaceEuler) == 3);
  // A manifold surface round those voxels joins them (one ball) or parts them (two).
  CHECK(Field(out, vtkCBC3DArrayNames::ImagePinchesJoinedEuler) == 2);
  CHECK(Field(out, vtkCBC3DArrayNames::ImagePinchesPartedEuler) == 4);
  CHECK(Field(out, vtkCBC3DArrayNames::TissueImageSurfaceEuler, 1) == 2);
  CHECK(Field(out, vtkCBC3DArrayNames::TissueImagePinchesJoinedEuler, 1) == 2);
  CHECK(Field(out, vtkCBC3DArrayNames::TissueImagePinchesPartedEuler, 1) == 2);
  CHECK(Field(out, vtkCBC3DArrayNames::TissueFaceComponents, 1) == 0);
  CHECK(Field(out, vtkCBC3DArrayNames::TissueSurfaceEuler, 1) == 0);
}

// A cube of six tets around its diagonal 0-7, tets 0 and 3 (which share only the diagonal)
// labelled 2, the others 1: the body is a ball, each tissue two parts hinged on the diagonal.
// Then two tets of one label sharing only a vertex.
void TestTopology()
{
  namespace names = vtkCBC3DArrayNames;
  std::vector<std::array<double, 3>> corners;
  for (int c = 0; c < 8; ++c)
  {
    corners.push_back({ double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1) });
  }
  auto cube = MakeMesh(corners,
    { { 0, 1, 3, 7 }, { 0, 3, 2, 7 }, { 0, 2, 6, 7 }, { 0, 6, 4, 7 }, { 0, 4, 5, 7 }, { 0, 5, 1, 7 } },
    { 2, 1, 1, 2, 1, 1 });
  vtkNew<vtkCBC3DMeshQuality> quality;
  quality->SetInputData(cube);
  quality->Update();
  vtkUnstructuredGrid* out = quality->GetOutput();
  CHECK(Field(out, names::FaceComponents) == 1 && Field(out, names::VertexComponents) == 1);
  CHECK(Field(out, names::HingedParts) == 0);
  CHECK(Field(out, names::SurfaceEuler) == 2);
  // The body's surface is manifold; the diagonal is non-manifold in both tissues' surfaces.
  CHECK(Field(out, names::NonManifoldEdges) == 2);
  CHECK(Field(out, names::NonManifoldVertices) == 0);
  CHECK(Field(out, names::SolverReady) == 0);
  CHECK(out->GetFieldData()->GetArray(names::ImageSurfaceEuler) == nullptr);
  CHECK(out->GetFieldData()->GetArray(names::TissueImageSurfaceEuler) == nullptr);
  CHECK(out->GetFieldData()->GetArray(names::ImagePinchesJoinedEuler) == nullptr);
  CHECK(out->GetFieldData()->GetArray(names::TissueImagePinchesPartedEuler) == nullptr);
  for (vtkIdType i = 0; i < 2; ++i)
  {
    CHECK(Field(out, names::TissueLabel, i) == i + 1);
    CHECK(Field(out, names::TissueFaceComponents, i) == 2);
    CHECK(Field(out, names::TissueVertexComponents, i) == 1);
    CHECK(Field(out, names::TissueHingedParts, i) == 1);
    CHECK(Field(out, names::TissueNonManifoldEdges, i) == 1);
    CHECK(Field(out, names::TissueNonManifoldVertices, i) == 0);
    CHECK(Field(out, names::TissueSurfaceEuler, i) == 3); // two balls sharing an edge
  }

  // One non-manifold vertex, counted in the body's surface and in the tissue's.
  auto pinched = MakeMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { -1, 0, 0 }, { 0, -1, 0 },
                            { 0, 0, -1 } },
    { { 0, 1, 2, 3 }, { 0, 5, 4, 6 } }, { 4, 4 });
  quality->SetInputData(pinched);
  quality->Update();
  out = quality->GetOutput();
  CHECK(Field(out, names::FaceComponents) == 2 && Field(out, names::VertexComponents) == 1);
  CHECK(Field(out, names::HingedParts) == 1 && Field(out, names::TissueHingedParts) == 1);
  CHECK(Field(out, names::NonManifoldEdges) == 0);
  CHECK(Field(out, names::NonManifoldVertices) == 2);
  CHECK(Field(out, names::TissueNonManifoldVertices) == 1);
  CHECK(Field(out, names::SurfaceEuler) == 3);
  CHECK(Field(out, names::SolverReady) == 0);
}

void TestBadInput()
{
  auto mesh = MakeMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } }, { { 0, 1, 2, 3 } }, { 1 });
  mesh->GetCellData()->RemoveArray(vtkCBC3DArrayNames::Label);
  vtkNew<vtkCBC3DMeshQuality> quality;
  vtkNew<cbc3dtest::MessageCatcher> errors;
  quality->AddObserver(vtkCommand::ErrorEvent, errors);
  quality->SetInputData(mesh);
  quality->Update();
  CHECK(errors->Text.find("Label") != std::string::npos);
  CHECK(quality->GetOutput()->GetNumberOfCells() == 0);
}
} // namespace

int TestCBC3DMeshQuality(int, char*[])
{
  TestAngles();
  TestBlockHausdorff();
  TestTopology();
  TestBadInput();
  return cbc3dtest::Finish();
}
