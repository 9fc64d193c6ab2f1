#ifndef cbc3d_MeditWriter_h
#define cbc3d_MeditWriter_h

#include "cbc3d/base/Status.h"
#include "cbc3d/base/TaggedMesh.h"

#include <ostream>

namespace cbc3d
{
/// Writes a Medit .mesh file (ASCII, MeshVersionFormatted 2, as MMG and meshio read it):
/// Vertices (ref 0), Triangles with ref = TaggedSurface::Id of their boundary or interface
/// (the table is in comment lines at the top of the file), Tetrahedra with ref = tissue label.
Status WriteMedit(const TaggedMesh& mesh, std::ostream& out);
} // namespace cbc3d

#endif
