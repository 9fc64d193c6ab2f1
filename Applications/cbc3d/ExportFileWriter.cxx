#include "ExportFileWriter.h"

#include "CommandLine.h"
#include "ErrorCapture.h"
#include "GeometryOnlyFormats.h"
#include "MeshFileWriter.h"
#include "vtkCBC3DConvert.h"

#include "cbc3d/export/AtomicFile.h"

#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
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
  return WriteBytesAtomically(extension == ".stl" ? StlBytes(surfaces) : ObjText(surfaces), path, error);
}
