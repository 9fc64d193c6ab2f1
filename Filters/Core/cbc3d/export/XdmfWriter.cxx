#include "cbc3d/export/XdmfWriter.h"

#include "cbc3d/export/AtomicFile.h"
#include "cbc3d/export/BinaryFormats.h"
#include "cbc3d/export/Hdf5HeavyData.h"
#include "cbc3d/export/MeshExport.h"
#include "cbc3d/export/PendingFiles.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include <vector>

namespace cbc3d
{
namespace
{
// `text` with XML's special characters escaped (a file name in a DataItem).
std::string EscapeXml(const std::string& text)
{
  std::string escaped;
  for (const char c : text)
  {
    switch (c)
    {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

// A DataItem naming the dataset `set` of the .h5.
std::string HeavyItem(const std::string& h5, const char* set, std::size_t rows,
  std::size_t columns, bool integers)
{
  std::ostringstream item;
  item << "<DataItem Dimensions=\"" << rows << " " << columns << "\""
       << (integers ? " NumberType=\"Int\"" : "") << " Format=\"HDF\">" << h5 << ":" << set
       << "</DataItem>\n";
  return item.str();
}

void WriteLightData(const TaggedMesh& mesh, const std::string& h5, std::ostream& out)
{
  const std::size_t tets = mesh.Tets.size(), triangles = mesh.Triangles.size();
  const std::string tetTopology = "      <Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"" +
    std::to_string(tets) + "\" NodesPerElement=\"4\">\n        " +
    HeavyItem(h5, MeshTopology, tets, 4, true) + "      </Topology>\n";
  const char* geometry = "      <xi:include xpointer=\"xpointer(/Xdmf/Domain/Grid/Geometry)\" />\n";
  out << "<?xml version=\"1.0\"?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      << "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n  <Domain>\n"
      << "    <Grid Name=\"mesh\" GridType=\"Uniform\">\n"
      << tetTopology << "      <Geometry GeometryType=\"XYZ\">\n        "
      << HeavyItem(h5, MeshGeometry, mesh.Points.size(), 3, false)
      << "      </Geometry>\n    </Grid>\n";
  out << "    <Grid Name=\"tissues\" GridType=\"Uniform\">\n"
      << geometry << tetTopology
      << "      <Attribute Name=\"tissues\" AttributeType=\"Scalar\" Center=\"Cell\">\n        "
      << HeavyItem(h5, TissueValues, tets, 1, true) << "      </Attribute>\n    </Grid>\n";
  if (triangles > 0)
  {
    out << "    <Grid Name=\"surfaces\" GridType=\"Uniform\">\n"
        << geometry << "      <Topology TopologyType=\"Triangle\" NumberOfElements=\""
        << triangles << "\" NodesPerElement=\"3\">\n        "
        << HeavyItem(h5, SurfaceTopology, triangles, 3, true) << "      </Topology>\n"
        << "      <Attribute Name=\"surfaces\" AttributeType=\"Scalar\" Center=\"Cell\">\n        "
        << HeavyItem(h5, SurfaceValues, triangles, 1, true)
        << "      </Attribute>\n    </Grid>\n";
  }
  out << "  </Domain>\n</Xdmf>\n";
}

std::string FileName(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}
} // namespace

std::string XdmfHeavyDataPath(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return path + ".h5";
  return path.substr(0, dot) + ".h5";
}

Status WriteXdmf(const TaggedMesh& mesh, const std::string& path)
{
  if (mesh.Tets.empty())
    return Status::Error("the mesh has no tetrahedra to write");
  const Status fits = RequireInt32Tissues(mesh, "XDMF", "dolfinx's mesh tags are 32-bit integers");
  if (!fits.IsOk())
    return fits;
  const std::string h5 = XdmfHeavyDataPath(path);
  const std::string xdmfPart = TemporaryPath(path), h5Part = TemporaryPath(h5);
  const int xdmfSlot = PendingFiles::Add(xdmfPart), h5Slot = PendingFiles::Add(h5Part);
  const auto done = [&](const std::string& why) {
    if (!why.empty())
    {
      std::remove(xdmfPart.c_str());
      std::remove(h5Part.c_str());
    }
    PendingFiles::Forget(xdmfSlot);
    PendingFiles::Forget(h5Slot);
    return why.empty() ? Status::Ok() : Status::Error(why);
  };

  std::string error;
  const BinaryFormatWriters* writers = LoadBinaryFormatWriters(error);
  if (!writers)
    return done(error);
  std::string image;
  error = writers->MakeXdmfHeavyData(mesh, image);
  if (!error.empty())
    return done("'" + h5 + "': " + error);
  if (!WriteFileBytes(h5Part, image, error))
    return done("'" + h5 + "': " + error);
  {
    std::ostringstream out;
    WriteLightData(mesh, EscapeXml(FileName(h5)), out);
    if (!WriteFileBytes(xdmfPart, out.str(), error))
      return done(error);
  }
  if (!MoveIntoPlace(h5Part, h5, error))
    return done(error);
  if (!MoveIntoPlace(xdmfPart, path, error))
  {
    std::remove(h5.c_str()); // no .h5 without its .xdmf
    return done(error);
  }
  return done("");
}
} // namespace cbc3d
