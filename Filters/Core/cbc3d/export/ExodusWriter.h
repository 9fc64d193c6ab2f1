#ifndef cbc3d_ExodusWriter_h
#define cbc3d_ExodusWriter_h

#include "cbc3d/base/Status.h"
#include "cbc3d/base/TaggedMesh.h"

#include <string>
#include <vector>

namespace cbc3d
{
/// The Exodus II side (1..4) of each face of TetTopology.h's TetFaces on a 4-node TETRA: Exodus's
/// sides are (1,2,4), (2,3,4), (1,4,3), (1,3,2) (outward), that is TetFaces 013, 123, 203, 021
/// in order, each the same face with the same orientation.
constexpr int ExodusSide(int face)
{
  return face + 1;
}

/// The order in which the tets go into the Exodus element blocks: every tet of Tissues[0] in
/// mesh order, then every tet of Tissues[1], ... Exodus numbers its elements 1, 2, ... in this
/// order (a side set's elements are these numbers); result[e] is the tet of element e + 1.
std::vector<std::size_t> ExodusElementOrder(const TaggedMesh& mesh);

/// Writes the mesh to the file `path` as Exodus II (netCDF, 64-bit offset, large model):
/// coordx/coordy/coordz; an element block per tissue, id its label, named tissue_<label>,
/// "TETRA" with 4 nodes (connect<k>); a side set per surface, id Surface::Id, named as in the other formats
/// (boundary_<label>, interface_<a>_<b>), each triangle as the (element, side) of its tet;
/// elem_num_map gives each element's tet (1-based index in the mesh). Netcdf writes to a path,
/// not a stream: WriteExportFile calls this on its temporary file.
Status WriteExodus(const TaggedMesh& mesh, const std::string& path);
} // namespace cbc3d

#endif
