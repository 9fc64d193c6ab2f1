#include "MeshFileWriter.h"

#include "CommandLine.h"
#include "ErrorCapture.h"
#include "VtuWriter.h"

#include "cbc3d/export/AtomicFile.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkLongArray.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <functional>
#include <unistd.h>

namespace
{
// The mesh as files carry it, so that meshio, the converter FE users reach for, reads them:
// its field data without text arrays (the stop reasons; the JSON report keeps the words), and,
// for the legacy format, whose "vtkIdType" meshio does not know, the id counts as "long".
vtkSmartPointer<vtkUnstructuredGrid> ForMeshio(vtkUnstructuredGrid* mesh, bool legacy)
{
  auto copy = vtkSmartPointer<vtkUnstructuredGrid>::New();
  copy->ShallowCopy(mesh);
  vtkNew<vtkFieldData> fields;
  vtkFieldData* original = mesh->GetFieldData();
  for (int i = 0; i < original->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* array = vtkDataArray::SafeDownCast(original->GetAbstractArray(i));
    if (legacy && vtkIdTypeArray::SafeDownCast(array))
    {
      vtkNew<vtkLongArray> counts;
      counts->DeepCopy(array);
      counts->SetName(array->GetName());
      fields->AddArray(counts);
    }
    else if (array)
    {
      fields->AddArray(array);
    }
  }
  copy->SetFieldData(fields);
  return copy;
}
} // namespace

bool WriteMeshFile(
  vtkUnstructuredGrid* input, const std::string& path, int threads, std::string& error)
{
  const bool legacy = FileExtension(path) == ".vtk";
  const vtkSmartPointer<vtkUnstructuredGrid> mesh = ForMeshio(input, legacy);
  // VTK's writers make the file in memory and ours writes it out with every write checked:
  // VTK 9.2's XML writer crashes when a write to a full disk fails.
  vtkNew<ErrorCapture> capture;
  std::string bytes;
  if (legacy)
  {
    vtkNew<vtkUnstructuredGridWriter> writer;
    capture->Observe(writer);
    writer->SetInputData(mesh);
    writer->WriteToOutputStringOn();
    writer->SetFileTypeToBinary();
    writer->SetFileVersion(vtkUnstructuredGridWriter::VTK_LEGACY_READER_VERSION_4_2);
    if (writer->Write())
      bytes = writer->GetOutputStdString();
  }
  else if (!MakeVtuBytes(mesh, threads, bytes))
  {
    // What our writer does not reproduce byte for byte goes to VTK's.
    // Inline binary, never the default appended mode: VTK 9.2's XML reader cannot read
    // appended files over ~4 KB with Debian 12's libexpat (VTK issue 19258).
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    capture->Observe(writer);
    writer->SetInputData(mesh);
    writer->WriteToOutputStringOn();
    writer->SetDataModeToBinary();
    writer->SetCompressorTypeToZLib();
    if (writer->Write())
      bytes = writer->GetOutputString();
  }
  if (bytes.empty() || !capture->Error.empty())
  {
    error = "cannot write '" + path + "'" +
      (capture->Error.empty() ? std::string() : ": " + capture->Error);
    return false;
  }
  return WriteBytesAtomically(bytes, path, error);
}

bool WriteBytesAtomically(const std::string& bytes, const std::string& path, std::string& error)
{
  return cbc3d::WriteAtomically(path, error, [&](const std::string& temporary, std::string& message) {
    if (!cbc3d::WriteFileBytes(temporary, bytes, message))
    {
      message = "cannot write '" + path + "': " + message;
      return false;
    }
    return true;
  });
}

bool CanWriteBeside(const std::string& path, std::string& error)
{
  const std::size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  if (access(folder.c_str(), W_OK) != 0)
  {
    error = "cannot write '" + path + "': " + std::strerror(errno);
    return false;
  }
  return true;
}

bool WriteTextFile(const std::string& text, const std::string& path, std::string& error)
{
  return WriteBytesAtomically(text, path, error);
}
