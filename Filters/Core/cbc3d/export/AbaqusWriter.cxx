#include "cbc3d/export/AbaqusWriter.h"

#include "cbc3d/export/MeshExport.h"

#include <array>

namespace cbc3d
{
namespace
{
// TetFaces (VTK's faces 013, 123, 203, 021) as Abaqus C3D4 faces: S2 (1-4-2), S3 (2-4-3),
// S4 (3-4-1), S1 (1-2-3).
constexpr std::array<int, 4> AbaqusFace = { 2, 3, 4, 1 };

// Writes ids 16 to a line, as Abaqus's data lines allow.
void WriteIds(const std::vector<std::size_t>& ids, std::ostream& out)
{
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    out << ids[i] << (i + 1 == ids.size() || i % 16 == 15 ? "\n" : ", ");
  }
}

void WriteNodesAndElements(const TaggedMesh& mesh, std::ostream& out)
{
  out << "*NODE\n";
  for (std::size_t i = 0; i < mesh.Points.size(); ++i)
  {
    const Eigen::Vector3d& p = mesh.Points[i];
    out << i + 1 << ", " << p.x() << ", " << p.y() << ", " << p.z() << "\n";
  }
  out << "*ELEMENT, TYPE=C3D4\n";
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const Tet& q = mesh.Tets[t];
    out << t + 1 << ", " << q[0] + 1 << ", " << q[1] + 1 << ", " << q[2] + 1 << ", " << q[3] + 1
        << "\n";
  }
}

void WriteTissueSets(const TaggedMesh& mesh, std::ostream& out)
{
  for (const std::int32_t label : mesh.Tissues)
  {
    std::vector<std::size_t> ids;
    for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
    {
      if (mesh.Labels[t] == label)
        ids.push_back(t + 1);
    }
    out << "*ELSET, ELSET=tissue_" << LabelValue(mesh, label) << "\n";
    WriteIds(ids, out);
  }
}

void WriteSurface(const TaggedMesh& mesh, std::size_t s, std::ostream& out)
{
  std::array<std::vector<std::size_t>, 5> byFace; // index: Abaqus face 1..4
  for (std::size_t t = mesh.SurfaceStart[s]; t < mesh.SurfaceStart[s + 1]; ++t)
  {
    const TaggedTriangle& triangle = mesh.Triangles[t];
    byFace[AbaqusFace[triangle.Face]].push_back(static_cast<std::size_t>(triangle.Tet) + 1);
  }
  const std::string& name = mesh.Surfaces[s].Name;
  for (int face = 1; face <= 4; ++face)
  {
    if (!byFace[face].empty())
    {
      out << "*ELSET, ELSET=" << name << "_S" << face << "\n";
      WriteIds(byFace[face], out);
    }
  }
  out << "*SURFACE, TYPE=ELEMENT, NAME=" << name << "\n";
  for (int face = 1; face <= 4; ++face)
  {
    if (!byFace[face].empty())
      out << name << "_S" << face << ", S" << face << "\n";
  }
}
} // namespace

Status WriteAbaqus(const TaggedMesh& mesh, std::ostream& out)
{
  const Status ready = BeginExport(mesh, out);
  if (!ready.IsOk())
  {
    return ready;
  }
  out << "*HEADING\ncbc3d multi-tissue tetrahedral mesh\n";
  WriteNodesAndElements(mesh, out);
  WriteTissueSets(mesh, out);
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
  {
    WriteSurface(mesh, s, out);
  }
  return EndExport(out);
}
} // namespace cbc3d
