#include "ExportFileWriter.h"

#include "CommandLine.h"
#include "ErrorCapture.h"
#include "MeshFileWriter.h"
#include "vtkCBC3DConvert.h"

#include "cbc3d/AtomicFile.h"

#include <vtkCellData.h>
#include <vtkErrorCode.h>
#include <vtkNew.h>
#include <vtkOBJWriter.h>
#include <vtkPolyData.h>
#include <vtkSTLWriter.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridWriter.h>
#include <vtkXMLPolyDataWriter.h>

#include <functional>
#include <type_traits>

namespace
{
// .vtp and .vtk: VTK makes the file in memory (its XML writer crashes when a write to a full
// disk fails) and WriteBytesAtomically writes it out with every write checked.
template <typename Writer>
bool WriteInMemory(Writer* writer, const std::string& path, std::string& error)
{
  vtkNew<ErrorCapture> capture;
  capture->Observe(writer);
  writer->WriteToOutputStringOn();
  std::string bytes;
  if (writer->Write() && capture->Error.empty())
  {
    if constexpr (std::is_base_of<vtkDataWriter, Writer>::value)
      bytes = writer->GetOutputStdString();
    else
      bytes = writer->GetOutputString();
  }
  if (bytes.empty())
  {
    error = "cannot write '" + path + "'" + (capture->Error.empty() ? std::string() : ": " + capture->Error);
    return false;
  }
  return WriteBytesAtomically(bytes, path, error);
}

bool WriteXmlSurfaces(vtkPolyData* surfaces, const std::string& path, std::string& error)
{
  // Inline binary, as for .vtu: VTK 9.2 cannot read back large appended files here.
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(surfaces);
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToZLib();
  return WriteInMemory(writer.Get(), path, error);
}

bool WriteLegacySurfaces(vtkPolyData* surfaces, const std::string& path, std::string& error)
{
  // An unstructured grid of triangles, not POLYDATA, which meshio's legacy reader refuses.
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(surfaces->GetPoints());
  grid->SetCells(VTK_TRIANGLE, surfaces->GetPolys());
  grid->GetCellData()->ShallowCopy(surfaces->GetCellData());
  vtkNew<vtkUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  writer->SetFileTypeToBinary();
  writer->SetFileVersion(vtkUnstructuredGridWriter::VTK_LEGACY_READER_VERSION_4_2);
  return WriteInMemory(writer.Get(), path, error);
}

// .stl and .obj: VTK's writers take only a file name; they report a failed write through
// their error code (a full disk: vtkErrorCode::OutOfDiskSpaceError) or an error event.
template <typename Writer>
bool WriteToFile(vtkPolyData* surfaces, const std::string& path, std::string& error)
{
  return cbc3d::WriteAtomically(path, error, [&](const std::string& temporary, std::string& message) {
    vtkNew<Writer> writer;
    vtkNew<ErrorCapture> capture;
    capture->Observe(writer);
    writer->SetInputData(surfaces);
    writer->SetFileName(temporary.c_str());
    if constexpr (std::is_same<Writer, vtkSTLWriter>::value)
      writer->SetFileTypeToBinary();
    const int ok = writer->Write();
    if (!ok || !capture->Error.empty() || writer->GetErrorCode() != vtkErrorCode::NoError)
    {
      const unsigned long code = writer->GetErrorCode();
      message = "cannot write '" + path + "': " +
        (!capture->Error.empty() ? capture->Error
                                 : code != vtkErrorCode::NoError ? vtkErrorCode::GetStringFromErrorCode(code)
                                                                 : std::string("the writer failed"));
      return false;
    }
    return true;
  });
}
} // namespace

bool WriteSurfaceFile(const cbc3d::TaggedMesh& mesh, const std::string& path, std::string& error)
{
  vtkNew<vtkPolyData> surfaces;
  vtkCBC3DConvert::ToPolyData(mesh, surfaces);
  const std::string extension = FileExtension(path);
  if (extension == ".vtp")
    return WriteXmlSurfaces(surfaces, path, error);
  if (extension == ".vtk")
    return WriteLegacySurfaces(surfaces, path, error);
  if (extension == ".stl")
    return WriteToFile<vtkSTLWriter>(surfaces, path, error);
  return WriteToFile<vtkOBJWriter>(surfaces, path, error);
}
