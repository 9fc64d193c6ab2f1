#include "cbc3d/export/GmshWriter.h"

#include "cbc3d/export/MeshExport.h"

namespace cbc3d
{
namespace
{
constexpr int GmshTriangle = 2;
constexpr int GmshTetrahedron = 4;

void WritePhysicalNames(const TaggedMesh& mesh, std::ostream& out)
{
  out << "$PhysicalNames\n" << mesh.Tissues.size() + mesh.Surfaces.size() << "\n";
  for (const TaggedSurface& surface : mesh.Surfaces)
  {
    out << "2 " << surface.Id << " \"" << surface.Name << "\"\n";
  }
  for (const std::int32_t label : mesh.Tissues)
  {
    out << "3 " << LabelValue(mesh, label) << " \"tissue_" << LabelValue(mesh, label) << "\"\n";
  }
  out << "$EndPhysicalNames\n";
}

// The bounding box of every point, written for each entity: readers only use it as a hint.
void WriteBox(const TaggedMesh& mesh, std::ostream& out)
{
  Eigen::Vector3d low = Eigen::Vector3d::Constant(0.0);
  Eigen::Vector3d high = low;
  if (!mesh.Points.empty())
  {
    low = high = mesh.Points[0];
  }
  for (const Eigen::Vector3d& p : mesh.Points)
  {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  out << low.x() << " " << low.y() << " " << low.z() << " " << high.x() << " " << high.y() << " "
      << high.z();
}

void WriteEntities41(const TaggedMesh& mesh, std::ostream& out)
{
  out << "$Entities\n0 0 " << mesh.Surfaces.size() << " " << mesh.Tissues.size() << "\n";
  for (const TaggedSurface& surface : mesh.Surfaces)
  {
    out << surface.Id << " ";
    WriteBox(mesh, out);
    out << " 1 " << surface.Id << " 0\n";
  }
  for (const std::int32_t label : mesh.Tissues)
  {
    out << LabelValue(mesh, label) << " ";
    WriteBox(mesh, out);
    out << " 1 " << LabelValue(mesh, label) << " 0\n";
  }
  out << "$EndEntities\n";
}

void WriteNodes41(const TaggedMesh& mesh, std::ostream& out)
{
  const std::size_t n = mesh.Points.size();
  out << "$Nodes\n1 " << n << " 1 " << n << "\n3 " << LabelValue(mesh, mesh.Tissues.front()) << " 0 " << n << "\n";
  for (std::size_t i = 0; i < n; ++i)
  {
    out << i + 1 << "\n";
  }
  for (const Eigen::Vector3d& p : mesh.Points)
  {
    out << p.x() << " " << p.y() << " " << p.z() << "\n";
  }
  out << "$EndNodes\n";
}

// Elements 1..T are the triangles (surface by surface), then the tets (tissue by tissue).
void WriteElements41(const TaggedMesh& mesh, std::ostream& out)
{
  const std::size_t total = mesh.Triangles.size() + mesh.Tets.size();
  out << "$Elements\n" << mesh.Surfaces.size() + mesh.Tissues.size() << " " << total << " 1 "
      << total << "\n";
  std::size_t tag = 1;
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
  {
    out << "2 " << mesh.Surfaces[s].Id << " " << GmshTriangle << " "
        << mesh.SurfaceStart[s + 1] - mesh.SurfaceStart[s] << "\n";
    for (std::size_t t = mesh.SurfaceStart[s]; t < mesh.SurfaceStart[s + 1]; ++t)
    {
      const auto& p = mesh.Triangles[t].Points;
      out << tag++ << " " << p[0] + 1 << " " << p[1] + 1 << " " << p[2] + 1 << "\n";
    }
  }
  const std::vector<std::size_t> counts = TetsPerTissue(mesh);
  for (std::size_t k = 0; k < mesh.Tissues.size(); ++k)
  {
    out << "3 " << LabelValue(mesh, mesh.Tissues[k]) << " " << GmshTetrahedron << " " << counts[k] << "\n";
    for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
    {
      if (mesh.Labels[t] != mesh.Tissues[k])
        continue;
      const Tet& q = mesh.Tets[t];
      out << tag++ << " " << q[0] + 1 << " " << q[1] + 1 << " " << q[2] + 1 << " " << q[3] + 1 << "\n";
    }
  }
  out << "$EndElements\n";
}

void WriteNodes22(const TaggedMesh& mesh, std::ostream& out)
{
  out << "$Nodes\n" << mesh.Points.size() << "\n";
  for (std::size_t i = 0; i < mesh.Points.size(); ++i)
  {
    const Eigen::Vector3d& p = mesh.Points[i];
    out << i + 1 << " " << p.x() << " " << p.y() << " " << p.z() << "\n";
  }
  out << "$EndNodes\n";
}

// Each element carries two tags: its physical group and its elementary entity (the same).
void WriteElements22(const TaggedMesh& mesh, std::ostream& out)
{
  out << "$Elements\n" << mesh.Triangles.size() + mesh.Tets.size() << "\n";
  std::size_t tag = 1;
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
  {
    const int id = mesh.Surfaces[s].Id;
    for (std::size_t t = mesh.SurfaceStart[s]; t < mesh.SurfaceStart[s + 1]; ++t)
    {
      const auto& p = mesh.Triangles[t].Points;
      out << tag++ << " " << GmshTriangle << " 2 " << id << " " << id << " " << p[0] + 1 << " "
          << p[1] + 1 << " " << p[2] + 1 << "\n";
    }
  }
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const Tet& q = mesh.Tets[t];
    const std::int64_t label = LabelValue(mesh, mesh.Labels[t]);
    out << tag++ << " " << GmshTetrahedron << " 2 " << label << " " << label << " " << q[0] + 1
        << " " << q[1] + 1 << " " << q[2] + 1 << " " << q[3] + 1 << "\n";
  }
  out << "$EndElements\n";
}
} // namespace

Status WriteGmsh(const TaggedMesh& mesh, std::ostream& out, bool version22)
{
  const Status ready = BeginExport(mesh, out);
  if (!ready.IsOk())
  {
    return ready;
  }
  if (LabelValue(mesh, mesh.Tissues.front()) <= 0)
  {
    return Status::Error("Gmsh needs positive physical tags, but tissue label " +
      std::to_string(LabelValue(mesh, mesh.Tissues.front())) + " is not");
  }
  const Status fits = RequireInt32Tissues(mesh, "Gmsh", "its physical and entity tags are 32-bit integers");
  if (!fits.IsOk())
  {
    return fits;
  }
  out << "$MeshFormat\n" << (version22 ? "2.2" : "4.1") << " 0 8\n$EndMeshFormat\n";
  WritePhysicalNames(mesh, out);
  if (version22)
  {
    WriteNodes22(mesh, out);
    WriteElements22(mesh, out);
  }
  else
  {
    WriteEntities41(mesh, out);
    WriteNodes41(mesh, out);
    WriteElements41(mesh, out);
  }
  return EndExport(out);
}
} // namespace cbc3d
