#ifndef cbc3d_FEBioWriter_h
#define cbc3d_FEBioWriter_h

#include "cbc3d/base/Status.h"
#include "cbc3d/base/TaggedMesh.h"

#include <ostream>

namespace cbc3d
{
/// Writes an FEBio model (.feb, febio_spec 4.0, solid module): Mesh/Nodes "all" (ids from 1);
/// an Elements block of type tet4 per tissue, named tissue_<label> (VTK's node order, positive
/// volumes); a Surface of tri3 facets per boundary and interface (boundary_<label>,
/// interface_<a>_<b>; each facet's normal from its first side into its second); and per tissue
/// a SolidDomain tissue_<label> with a placeholder material tissue_<label>: "isotropic elastic",
/// density 1, E 1, v 0.3, meant to be replaced in FEBio Studio or by editing the file.
Status WriteFEBio(const TaggedMesh& mesh, std::ostream& out);
} // namespace cbc3d

#endif
