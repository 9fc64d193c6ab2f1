#ifndef cbc3d_MeshFileWriter_h
#define cbc3d_MeshFileWriter_h

#include <functional>
#include <string>

class vtkUnstructuredGrid;

/// Writes .vtu (VTK XML, inline binary, zlib) or .vtk (legacy 4.2, binary), every array but
/// the field data's text (the stop reasons, which meshio cannot read; the report has them). The file appears
/// whole or not at all: it is written under a temporary name in the same folder, then renamed.
bool WriteMeshFile(vtkUnstructuredGrid* mesh, const std::string& path, std::string& error);

/// Checks that the folder of `path` exists and is writable, with a one-line message if not.
bool CanWriteBeside(const std::string& path, std::string& error);

/// Runs `write(temporary, error)` on a temporary name beside `path` and renames the file into
/// place when it succeeds, so that `path` appears whole or not at all.
bool WriteAtomically(const std::string& path, std::string& error,
  const std::function<bool(const std::string&, std::string&)>& write);

/// Writes text the same all-or-nothing way.
bool WriteTextFile(const std::string& text, const std::string& path, std::string& error);

#endif
