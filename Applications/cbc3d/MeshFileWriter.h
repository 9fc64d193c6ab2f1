#ifndef cbc3d_MeshFileWriter_h
#define cbc3d_MeshFileWriter_h

#include <string>

class vtkUnstructuredGrid;

/// Writes .vtu (VTK XML, inline binary, zlib) or .vtk (legacy 4.2, binary), every array but
/// the field data's text (the stop reasons, which meshio cannot read; the report has them). The file appears
/// whole or not at all: it is written under a temporary name in the same folder, then renamed.
/// .vtu files are VTK's writer's bytes, compressed on `threads` OpenMP threads (0: all).
bool WriteMeshFile(
  vtkUnstructuredGrid* mesh, const std::string& path, int threads, std::string& error);

/// Checks that the folder of `path` exists and is writable, with a one-line message if not.
bool CanWriteBeside(const std::string& path, std::string& error);

/// Writes text the same all-or-nothing way.
bool WriteTextFile(const std::string& text, const std::string& path, std::string& error);

/// Writes `bytes` (a file VTK made in memory) to `path`, whole or not at all, every write checked.
bool WriteBytesAtomically(const std::string& bytes, const std::string& path, std::string& error);

#endif
