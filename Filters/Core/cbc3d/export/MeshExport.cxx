#include "cbc3d/export/MeshExport.h"

#include "cbc3d/export/AbaqusWriter.h"
#include "cbc3d/export/BinaryFormats.h"
#include "cbc3d/export/FEBioWriter.h"
#include "cbc3d/export/GmshWriter.h"
#include "cbc3d/export/MeditWriter.h"
#include "cbc3d/export/XdmfWriter.h"

#include "cbc3d/export/AtomicFile.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>

namespace cbc3d
{
bool IsExportExtension(const std::string& extension)
{
  return extension == ".msh" || extension == ".inp" || extension == ".mesh" ||
    extension == ".feb" || extension == ".xdmf" || extension == ".exo";
}

std::string ExportExtensions()
{
  return ".msh, .inp, .mesh, .feb, .xdmf, .exo";
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
    return Status::Error(
      "XDMF (.xdmf) is written to files (its heavy data in an HDF5 .h5 beside it), not to a stream");
  if (extension == ".exo")
    return Status::Error("Exodus II (.exo) is written to a file (netCDF), not to a stream");
  return Status::Error("no solver format for the extension '" + extension + "'");
}

std::string LowerCaseExtension(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return "";
  }
  std::string extension = path.substr(dot);
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

Status WriteExportFile(const TaggedMesh& mesh, const std::string& path, bool gmsh22)
{
  if (LowerCaseExtension(path) == ".xdmf")
  {
    // Two files, the .xdmf and its .h5: XdmfWriter makes both appear whole or neither.
    const Status status = WriteXdmf(mesh, path);
    return status.IsOk() ? status
                         : Status::Error("cannot write '" + path + "': " + status.GetMessage());
  }
  std::string error;
  const bool written =
    WriteAtomically(path, error, [&](const std::string& temporary, std::string& message) {
      const std::string extension = LowerCaseExtension(path);
      if (extension == ".exo")
      {
        // netCDF writes to a path: the temporary file's, renamed into place once closed.
        std::string why;
        const BinaryFormatWriters* writers = LoadBinaryFormatWriters(why);
        const Status status = writers ? writers->WriteExodus(mesh, temporary) : Status::Error(why);
        if (!status.IsOk())
          message = "cannot write '" + path + "': " + status.GetMessage();
        return status.IsOk();
      }
      errno = 0;
      std::ofstream out(temporary, std::ios::binary);
      if (!out)
      {
        message = "cannot write '" + path + "': " + std::strerror(errno);
        return false;
      }
      const Status status = WriteExport(mesh, extension, out, gmsh22);
      out.close();
      if (!status.IsOk() || !out)
      {
        // A failed write leaves errno's reason (a full disk: ENOSPC, a size limit: EFBIG).
        message = "cannot write '" + path + "': " +
          (!out && errno != 0 ? std::string(std::strerror(errno))
                              : status.IsOk() ? std::string("the write failed") : status.GetMessage());
        return false;
      }
      return true;
    });
  return written ? Status::Ok() : Status::Error(error);
}
} // namespace cbc3d
