#ifndef cbc3d_ExportFileWriter_h
#define cbc3d_ExportFileWriter_h

#include "cbc3d/base/TaggedMesh.h"

#include <string>

/// Writes the boundary and interface triangles with their `BoundaryLabels` and `SurfaceId` cell
/// arrays (.vtp: VTK XML, inline binary; .vtk: legacy 4.2, binary), or their geometry alone
/// (.stl binary, .obj, which have no cell arrays), whole or not at all.
bool WriteSurfaceFile(const cbc3d::TaggedMesh& mesh, const std::string& path, std::string& error);

#endif
