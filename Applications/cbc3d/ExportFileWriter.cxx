#include "ExportFileWriter.h"

#include "CommandLine.h"
#include "ErrorCapture.h"
#include "vtkCBC3DConvert.h"

#include "cbc3d/AtomicFile.h"

#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkOBJWriter.h>
#include <vtkPolyData.h>
#include <vtkSTLWriter.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridWriter.h>
#include <vtkXMLPolyDataWriter.h>

#include <functional>

namespace
{
// Runs one VTK writer, set up like the mesh files' writers, on `surfaces`.
template <typename Writer>
int Write(vtkPolyData* surfaces, const std::string& name, ErrorCapture* capture,
  const std::function<void(Writer*)>& setUp = nullptr)
{
  vtkNew<Writer> writer;
  capture->Observe(writer);
  writer->SetInputData(surfaces);
  writer->SetFileName(name.c_str());
  if (setUp)
    setUp(writer);
  return writer->Write();
}

int WriteSurfaces(vtkPolyData* surfaces, const std::string& extension, const std::string& name,
  ErrorCapture* capture)
{
  if (extension == ".vtp")
  {
    // Inline binary, as for .vtu: VTK 9.2 cannot read back large appended files here.
    return Write<vtkXMLPolyDataWriter>(surfaces, name, capture, [](vtkXMLPolyDataWriter* w) {
      w->SetDataModeToBinary();
      w->SetCompressorTypeToZLib();
    });
  }
  if (extension == ".vtk")
  {
    // An unstructured grid of triangles, not POLYDATA, which meshio's legacy reader refuses.
    vtkNew<vtkUnstructuredGrid> grid;
    grid->SetPoints(surfaces->GetPoints());
    grid->SetCells(VTK_TRIANGLE, surfaces->GetPolys());
    grid->GetCellData()->ShallowCopy(surfaces->GetCellData());
    vtkNew<vtkUnstructuredGridWriter> writer;
    capture->Observe(writer);
    writer->SetInputData(grid);
    writer->SetFileName(name.c_str());
    writer->SetFileTypeToBinary();
    writer->SetFileVersion(vtkUnstructuredGridWriter::VTK_LEGACY_READER_VERSION_4_2);
    return writer->Write();
  }
  if (extension == ".stl")
  {
    return Write<vtkSTLWriter>(
      surfaces, name, capture, [](vtkSTLWriter* w) { w->SetFileTypeToBinary(); });
  }
  return Write<vtkOBJWriter>(surfaces, name, capture);
}
} // namespace

bool WriteSurfaceFile(const cbc3d::TaggedMesh& mesh, const std::string& path, std::string& error)
{
  vtkNew<vtkPolyData> surfaces;
  vtkCBC3DConvert::ToPolyData(mesh, surfaces);
  return cbc3d::WriteAtomically(path, error, [&](const std::string& temporary, std::string& message) {
    vtkNew<ErrorCapture> capture;
    const int ok = WriteSurfaces(surfaces, FileExtension(path), temporary, capture);
    if (!ok || !capture->Error.empty())
    {
      message = "cannot write '" + path + "'" +
        (capture->Error.empty() ? std::string() : ": " + capture->Error);
      return false;
    }
    return true;
  });
}
