#ifndef cbc3d_XdmfWriter_h
#define cbc3d_XdmfWriter_h

#include "cbc3d/base/Status.h"
#include "cbc3d/base/TaggedMesh.h"

#include <string>

namespace cbc3d
{
/// The HDF5 file beside an .xdmf: `path` with its extension replaced by ".h5" (mesh.xdmf ->
/// mesh.h5), or ".h5" appended where it has none.
std::string XdmfHeavyDataPath(const std::string& path);

/// Writes XDMF 3 as dolfinx's XDMFFile writes it with its default encoding (HDF5): the light
/// data (XML) to `path` and the heavy data to the HDF5 file XdmfHeavyDataPath(path) beside it,
/// each DataItem Format="HDF" naming that file (by its name alone, relative to the .xdmf) and a
/// dataset in it: the grid "mesh" (read_mesh(name="mesh"); /Mesh/mesh/topology, int64 N x 4,
/// and /Mesh/mesh/geometry, float64 M x 3), the cell tags "tissues" (value = tissue label;
/// /MeshTags/tissues/Values, int32 N x 1, on the mesh's topology) and the facet tags "surfaces"
/// (value = TaggedSurface::Id, the boundaries and interfaces in the order of
/// TaggedMesh::Surfaces; /MeshTags/surfaces/topology and Values), both read with
/// read_meshtags(mesh, name). Both files appear whole or neither does: each is written to a
/// temporary name beside it, the .h5 renamed into place first and the .xdmf last; on failure
/// both temporaries are removed (and the new .h5 too where the .xdmf's rename fails). The HDF5 data carries no time stamps: the same mesh gives the
/// same bytes.
Status WriteXdmf(const TaggedMesh& mesh, const std::string& path);
} // namespace cbc3d

#endif
