#include "cbc3d/XdmfWriter.h"

#include "cbc3d/MeshExport.h"

namespace cbc3d
{
namespace
{
void WriteTetTopology(const TaggedMesh& mesh, std::ostream& out)
{
  const std::size_t n = mesh.Tets.size();
  out << "      <Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"" << n
      << "\" NodesPerElement=\"4\">\n        <DataItem Dimensions=\"" << n
      << " 4\" NumberType=\"Int\" Format=\"XML\">\n";
  for (const Tet& q : mesh.Tets)
  {
    out << q[0] << " " << q[1] << " " << q[2] << " " << q[3] << "\n";
  }
  out << "        </DataItem>\n      </Topology>\n";
}

void WriteMeshGrid(const TaggedMesh& mesh, std::ostream& out)
{
  out << "    <Grid Name=\"mesh\" GridType=\"Uniform\">\n";
  WriteTetTopology(mesh, out);
  out << "      <Geometry GeometryType=\"XYZ\">\n        <DataItem Dimensions=\""
      << mesh.Points.size() << " 3\" Format=\"XML\">\n";
  for (const Eigen::Vector3d& p : mesh.Points)
  {
    out << p.x() << " " << p.y() << " " << p.z() << "\n";
  }
  out << "        </DataItem>\n      </Geometry>\n    </Grid>\n";
}

// A tag grid's values as dolfinx writes them: an "N 1" cell attribute named like the grid.
template <typename Values>
void WriteTagValues(const char* name, std::size_t n, Values values, std::ostream& out)
{
  out << "      <Attribute Name=\"" << name << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
      << "        <DataItem Dimensions=\"" << n << " 1\" Format=\"XML\">\n";
  for (std::size_t i = 0; i < n; ++i)
  {
    out << values(i) << "\n";
  }
  out << "        </DataItem>\n      </Attribute>\n    </Grid>\n";
}

void WriteCellTags(const TaggedMesh& mesh, std::ostream& out)
{
  out << "    <Grid Name=\"tissues\" GridType=\"Uniform\">\n"
      << "      <xi:include xpointer=\"xpointer(/Xdmf/Domain/Grid/Geometry)\" />\n";
  WriteTetTopology(mesh, out);
  WriteTagValues("tissues", mesh.Tets.size(), [&](std::size_t t) { return mesh.Labels[t]; }, out);
}

void WriteFacetTags(const TaggedMesh& mesh, std::ostream& out)
{
  const std::size_t n = mesh.Triangles.size();
  out << "    <Grid Name=\"surfaces\" GridType=\"Uniform\">\n"
      << "      <xi:include xpointer=\"xpointer(/Xdmf/Domain/Grid/Geometry)\" />\n"
      << "      <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << n
      << "\" NodesPerElement=\"3\">\n        <DataItem Dimensions=\"" << n
      << " 3\" NumberType=\"Int\" Format=\"XML\">\n";
  for (const TaggedTriangle& triangle : mesh.Triangles)
  {
    out << triangle.Points[0] << " " << triangle.Points[1] << " " << triangle.Points[2] << "\n";
  }
  out << "        </DataItem>\n      </Topology>\n";
  std::vector<int> ids(n);
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
  {
    for (std::size_t t = mesh.SurfaceStart[s]; t < mesh.SurfaceStart[s + 1]; ++t)
      ids[t] = mesh.Surfaces[s].Id;
  }
  WriteTagValues("surfaces", n, [&](std::size_t t) { return ids[t]; }, out);
}
} // namespace

Status WriteXdmf(const TaggedMesh& mesh, std::ostream& out)
{
  const Status ready = BeginExport(mesh, out);
  if (!ready.IsOk())
  {
    return ready;
  }
  out << "<?xml version=\"1.0\"?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      << "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n  <Domain>\n";
  WriteMeshGrid(mesh, out);
  WriteCellTags(mesh, out);
  if (!mesh.Triangles.empty())
  {
    WriteFacetTags(mesh, out);
  }
  out << "  </Domain>\n</Xdmf>\n";
  return EndExport(out);
}
} // namespace cbc3d
