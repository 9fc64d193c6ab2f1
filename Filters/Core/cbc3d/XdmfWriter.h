#ifndef cbc3d_XdmfWriter_h
#define cbc3d_XdmfWriter_h

#include "cbc3d/Status.h"
#include "cbc3d/TaggedMesh.h"

#include <ostream>

namespace cbc3d
{
/// Writes XDMF 3 as dolfinx writes it with ASCII encoding, every value inline in the one file
/// (dolfinx 0.5 reads inline XML data items; no HDF5 file to carry along): the grid "mesh"
/// (read_mesh(name="mesh")), the cell tags "tissues" (value = tissue label) and the facet tags
/// "surfaces" (value = TaggedSurface::Id, the boundaries and interfaces in the order of
/// TaggedMesh::Surfaces), both read with read_meshtags(mesh, name).
Status WriteXdmf(const TaggedMesh& mesh, std::ostream& out);
} // namespace cbc3d

#endif
