#ifndef cbc3d_MeshExport_h
#define cbc3d_MeshExport_h

// Stage: export. Takes the tagged mesh (base/TaggedMesh.h); gives the solver files, one writer a
// format (Gmsh, Abaqus, Medit, FEBio, XDMF; Exodus II and XDMF's HDF5 in a library loaded when
// needed, BinaryFormats.h), each written whole or not at all (AtomicFile.h, PendingFiles.h).

#include "cbc3d/base/Status.h"
#include "cbc3d/base/TaggedMesh.h"

#include <ostream>
#include <string>

namespace cbc3d
{
/// The solver formats the tagged mesh goes to, chosen by file extension: .msh (Gmsh 4.1, or
/// 2.2 with `gmsh22`), .inp (Abaqus), .mesh (Medit), .feb (FEBio), .xdmf (dolfinx's XDMF with
/// an HDF5 .h5 beside it) and .exo (Exodus II, netCDF): the last two written to files only, by
/// WriteExportFile.
bool IsExportExtension(const std::string& extension);

/// The extensions above, for messages: ".msh, .inp, .mesh, .feb, .xdmf, .exo".
std::string ExportExtensions();

/// What every writer does first: an error for a mesh with no tets, else full double precision
/// on `out` (every coordinate read back exactly).
Status BeginExport(const TaggedMesh& mesh, std::ostream& out);

/// What every writer returns: an error if the stream failed.
Status EndExport(const std::ostream& out);

/// Writes the mesh in the format of `extension` (lower case, with its dot); an error for .exo
/// and .xdmf, which netCDF and HDF5 write to paths (WriteExportFile).
Status WriteExport(
  const TaggedMesh& mesh, const std::string& extension, std::ostream& out, bool gmsh22 = false);
/// The lower-cased extension of a file name with its dot (".msh"), "" if none.
std::string LowerCaseExtension(const std::string& path);

/// Writes the file `path` in the format of its extension, whole or not at all (AtomicFile.h);
/// for .xdmf, the .xdmf and its .h5 (XdmfWriter.h), both whole or neither.
Status WriteExportFile(const TaggedMesh& mesh, const std::string& path, bool gmsh22 = false);
} // namespace cbc3d

#endif
