// The tissue surfaces filter and the solver-format writer on two unit cubes of tissues 1 and 2
// (Kuhn tets): 22 triangles, 10 on each boundary and 2 on the interface, whose normals point
// from tissue 1 into tissue 2; the writer's file, and the errors of both on bad input.
#include "CBC3DTestUtilities.h"
#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DMeshWriter.h"
#include "vtkCBC3DTissueSurfaces.h"

#include "../Core/TestMeshes.h"

#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace
{
vtkSmartPointer<vtkUnstructuredGrid> TwoCubes(bool withLabels = true)
{
  const cbc3d::TetMesh cubes = cbc3d::testing::KuhnGrid(
    2, 1, 1, [](int, int, int) { return true; }, [](int x, int, int, int) { return x + 1; });
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  for (const Eigen::Vector3d& p : cubes.Points)
    points->InsertNextPoint(p.data());
  grid->SetPoints(points);
  vtkNew<vtkIntArray> labels;
  labels->SetName(vtkCBC3DArrayNames::Label);
  for (std::size_t t = 0; t < cubes.Tets.size(); ++t)
  {
    const vtkIdType ids[4] = { cubes.Tets[t][0], cubes.Tets[t][1], cubes.Tets[t][2], cubes.Tets[t][3] };
    grid->InsertNextCell(VTK_TETRA, 4, ids);
    labels->InsertNextValue(cubes.Labels[t]);
  }
  if (withLabels)
    grid->GetCellData()->AddArray(labels);
  return grid;
}

void TestSurfaces()
{
  vtkNew<vtkCBC3DTissueSurfaces> filter;
  filter->SetInputData(TwoCubes());
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  CHECK(out->GetNumberOfCells() == 22);
  CHECK(out->GetNumberOfPoints() == 12);
  vtkDataArray* sides = out->GetCellData()->GetArray(vtkCBC3DArrayNames::BoundaryLabels);
  vtkDataArray* ids = out->GetCellData()->GetArray(vtkCBC3DArrayNames::SurfaceId);
  CHECK(sides && sides->GetNumberOfComponents() == 2 && ids);
  if (!sides || !ids)
    return;
  int counts[4] = { 0, 0, 0, 0 };
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    const int a = static_cast<int>(sides->GetComponent(c, 0));
    const int b = static_cast<int>(sides->GetComponent(c, 1));
    const int id = static_cast<int>(ids->GetTuple1(c));
    CHECK((a == 1 && b == 0 && id == 1) || (a == 2 && b == 0 && id == 2) || (a == 1 && b == 2 && id == 3));
    ++counts[id];
    if (id == 3)
    {
      // On the plane x = 1, its normal along +x: from tissue 1 into tissue 2.
      double p[3][3];
      vtkIdType n = 0;
      const vtkIdType* v = nullptr;
      out->GetCellPoints(c, n, v);
      for (int k = 0; k < 3; ++k)
        out->GetPoint(v[k], p[k]);
      const double nx = (p[1][1] - p[0][1]) * (p[2][2] - p[0][2]) - (p[1][2] - p[0][2]) * (p[2][1] - p[0][1]);
      CHECK(p[0][0] == 1.0 && p[1][0] == 1.0 && p[2][0] == 1.0 && nx > 0.0);
    }
  }
  CHECK(counts[1] == 10 && counts[2] == 10 && counts[3] == 2);
  std::ostringstream text;
  filter->SetOutsideLabel(5);
  filter->Print(text);
  CHECK(text.str().find("OutsideLabel: 5") != std::string::npos);
}

void TestSurfaceErrors()
{
  for (const bool withLabels : { true, false })
  {
    vtkNew<vtkCBC3DTissueSurfaces> filter;
    vtkNew<cbc3dtest::MessageCatcher> errors;
    filter->AddObserver(vtkCommand::ErrorEvent, errors);
    filter->SetInputData(TwoCubes(withLabels));
    filter->SetOutsideLabel(2); // a tissue label
    filter->Update();
    CHECK(errors->Text.find(withLabels ? "outside label 2" : "Label") != std::string::npos);
    CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  }
}

std::string ReadFile(const std::string& path)
{
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return in ? text.str() : std::string();
}

void TestWriter()
{
  const char* folder = std::getenv("CBC3D_TEST_OUTPUT");
  const std::string base = std::string(folder ? folder : ".") + "/TestCBC3DMeshWriter";
  vtkNew<vtkCBC3DMeshWriter> writer;
  writer->SetInputData(TwoCubes());
  writer->SetFileName((base + ".msh").c_str());
  writer->MshVersion22On();
  CHECK(writer->Write() == 1);
  const std::string msh = ReadFile(base + ".msh");
  CHECK(msh.find("$MeshFormat\n2.2 0 8\n") == 0);
  CHECK(msh.find("2 3 \"interface_1_2\"") != std::string::npos);
  CHECK(msh.find("$Elements\n34\n") != std::string::npos);
  std::remove((base + ".msh").c_str());

  for (const std::string name : { ".stl", ".inp" })
  {
    // A bad extension, then a mesh without labels: one error each, no file.
    vtkNew<vtkCBC3DMeshWriter> bad;
    vtkNew<cbc3dtest::MessageCatcher> errors;
    bad->AddObserver(vtkCommand::ErrorEvent, errors);
    bad->SetInputData(TwoCubes(name == ".stl"));
    bad->SetFileName((base + name).c_str());
    bad->Write();
    CHECK(errors->Text.find(name == ".stl" ? "unknown extension" : "Label") != std::string::npos);
    CHECK(!std::ifstream(base + name).good());
  }
  std::ostringstream text;
  writer->Print(text);
  CHECK(text.str().find("MshVersion22: 1") != std::string::npos);
}
} // namespace

int TestCBC3DTissueSurfaces(int, char*[])
{
  TestSurfaces();
  TestSurfaceErrors();
  TestWriter();
  return cbc3dtest::Finish();
}
