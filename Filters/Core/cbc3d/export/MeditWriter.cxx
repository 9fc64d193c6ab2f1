#include "cbc3d/export/MeditWriter.h"

#include "cbc3d/export/MeshExport.h"

namespace cbc3d
{
namespace
{
// Medit has no names: the comment lines say which ref is which surface.
void WriteRefTable(const TaggedMesh& mesh, std::ostream& out)
{
  out << "# cbc3d: Tetrahedra refs are tissue labels; Triangles refs are surfaces:\n";
  for (const TaggedSurface& surface : mesh.Surfaces)
  {
    out << "# " << surface.Id << " " << surface.Name << "\n";
  }
}
} // namespace

Status WriteMedit(const TaggedMesh& mesh, std::ostream& out)
{
  const Status ready = BeginExport(mesh, out);
  if (!ready.IsOk())
  {
    return ready;
  }
  const Status fits = RequireInt32Tissues(mesh, "Medit", "its element refs are 32-bit integers");
  if (!fits.IsOk())
  {
    return fits;
  }
  out << "MeshVersionFormatted 2\n";
  WriteRefTable(mesh, out);
  out << "Dimension 3\nVertices\n" << mesh.Points.size() << "\n";
  for (const Eigen::Vector3d& p : mesh.Points)
  {
    out << p.x() << " " << p.y() << " " << p.z() << " 0\n";
  }
  out << "Triangles\n" << mesh.Triangles.size() << "\n";
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
  {
    for (std::size_t t = mesh.SurfaceStart[s]; t < mesh.SurfaceStart[s + 1]; ++t)
    {
      const auto& p = mesh.Triangles[t].Points;
      out << p[0] + 1 << " " << p[1] + 1 << " " << p[2] + 1 << " " << mesh.Surfaces[s].Id << "\n";
    }
  }
  out << "Tetrahedra\n" << mesh.Tets.size() << "\n";
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const Tet& q = mesh.Tets[t];
    out << q[0] + 1 << " " << q[1] + 1 << " " << q[2] + 1 << " " << q[3] + 1 << " "
        << LabelValue(mesh, mesh.Labels[t]) << "\n";
  }
  out << "End\n";
  return EndExport(out);
}
} // namespace cbc3d
