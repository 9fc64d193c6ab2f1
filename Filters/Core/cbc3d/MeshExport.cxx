#include "cbc3d/MeshExport.h"

#include "cbc3d/AbaqusWriter.h"
#include "cbc3d/FEBioWriter.h"
#include "cbc3d/GmshWriter.h"
#include "cbc3d/MeditWriter.h"
#include "cbc3d/XdmfWriter.h"

#include <limits>

namespace cbc3d
{
bool IsExportExtension(const std::string& extension)
{
  return extension == ".msh" || extension == ".inp" || extension == ".mesh" ||
    extension == ".feb" || extension == ".xdmf";
}

std::string ExportExtensions()
{
  return ".msh, .inp, .mesh, .feb, .xdmf";
}

Status BeginExport(const TaggedMesh& mesh, std::ostream& out)
{
  if (mesh.Tets.empty())
  {
    return Status::Error("the mesh has no tetrahedra to write");
  }
  out.precision(std::numeric_limits<double>::max_digits10);
  return Status::Ok();
}

Status EndExport(const std::ostream& out)
{
  return out ? Status::Ok() : Status::Error("the stream failed while writing the mesh");
}

Status WriteExport(
  const TaggedMesh& mesh, const std::string& extension, std::ostream& out, bool gmsh22)
{
  if (extension == ".msh")
    return WriteGmsh(mesh, out, gmsh22);
  if (extension == ".inp")
    return WriteAbaqus(mesh, out);
  if (extension == ".mesh")
    return WriteMedit(mesh, out);
  if (extension == ".feb")
    return WriteFEBio(mesh, out);
  if (extension == ".xdmf")
    return WriteXdmf(mesh, out);
  return Status::Error("no solver format for the extension '" + extension + "'");
}
} // namespace cbc3d
