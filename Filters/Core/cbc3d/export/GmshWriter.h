#ifndef cbc3d_GmshWriter_h
#define cbc3d_GmshWriter_h

#include "cbc3d/base/Status.h"
#include "cbc3d/base/TaggedMesh.h"

#include <ostream>

namespace cbc3d
{
/// Writes a Gmsh .msh file (ASCII), version 4.1 or 2.2 (for older readers such as SOFA's).
/// Physical volumes: one per tissue, tag = its label (which must be positive), named
/// tissue_<label>. Physical surfaces: one per boundary and interface, tag = TaggedSurface::Id,
/// named boundary_<label> or interface_<a>_<b>. In 4.1 each physical group has its own
/// elementary entity with the same tag; every node sits on the first volume.
Status WriteGmsh(const TaggedMesh& mesh, std::ostream& out, bool version22 = false);
} // namespace cbc3d

#endif
