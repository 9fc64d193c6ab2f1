#include "cbc3d/export/FEBioWriter.h"

#include "cbc3d/export/MeshExport.h"

namespace cbc3d
{
namespace
{
// The placeholders (FEBio needs a material per domain to open the model).
void WriteMaterials(const TaggedMesh& mesh, std::ostream& out)
{
  out << "  <Material>\n";
  for (std::size_t k = 0; k < mesh.Tissues.size(); ++k)
  {
    out << "    <material id=\"" << k + 1 << "\" name=\"tissue_" << LabelValue(mesh, mesh.Tissues[k])
        << "\" type=\"isotropic elastic\">\n"
        << "      <density>1</density>\n      <E>1</E>\n      <v>0.3</v>\n    </material>\n";
  }
  out << "  </Material>\n";
}

void WriteNodes(const TaggedMesh& mesh, std::ostream& out)
{
  out << "    <Nodes name=\"all\">\n";
  for (std::size_t i = 0; i < mesh.Points.size(); ++i)
  {
    const Eigen::Vector3d& p = mesh.Points[i];
    out << "      <node id=\"" << i + 1 << "\">" << p.x() << "," << p.y() << "," << p.z()
        << "</node>\n";
  }
  out << "    </Nodes>\n";
}

// Elements keep their index in the mesh plus one as id, so ids match the other formats'.
void WriteElements(const TaggedMesh& mesh, std::ostream& out)
{
  for (const std::int32_t label : mesh.Tissues)
  {
    out << "    <Elements type=\"tet4\" name=\"tissue_" << LabelValue(mesh, label) << "\">\n";
    for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
    {
      if (mesh.Labels[t] != label)
        continue;
      const Tet& q = mesh.Tets[t];
      out << "      <elem id=\"" << t + 1 << "\">" << q[0] + 1 << "," << q[1] + 1 << ","
          << q[2] + 1 << "," << q[3] + 1 << "</elem>\n";
    }
    out << "    </Elements>\n";
  }
}

void WriteSurfaces(const TaggedMesh& mesh, std::ostream& out)
{
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
  {
    out << "    <Surface name=\"" << mesh.Surfaces[s].Name << "\">\n";
    for (std::size_t t = mesh.SurfaceStart[s]; t < mesh.SurfaceStart[s + 1]; ++t)
    {
      const auto& p = mesh.Triangles[t].Points;
      out << "      <tri3 id=\"" << t - mesh.SurfaceStart[s] + 1 << "\">" << p[0] + 1 << ","
          << p[1] + 1 << "," << p[2] + 1 << "</tri3>\n";
    }
    out << "    </Surface>\n";
  }
}
} // namespace

Status WriteFEBio(const TaggedMesh& mesh, std::ostream& out)
{
  const Status ready = BeginExport(mesh, out);
  if (!ready.IsOk())
  {
    return ready;
  }
  out << "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n<febio_spec version=\"4.0\">\n"
      << "  <Module type=\"solid\"/>\n";
  WriteMaterials(mesh, out);
  out << "  <Mesh>\n";
  WriteNodes(mesh, out);
  WriteElements(mesh, out);
  WriteSurfaces(mesh, out);
  out << "  </Mesh>\n  <MeshDomains>\n";
  for (const std::int32_t label : mesh.Tissues)
  {
    const std::int64_t value = LabelValue(mesh, label);
    out << "    <SolidDomain name=\"tissue_" << value << "\" mat=\"tissue_" << value << "\"/>\n";
  }
  out << "  </MeshDomains>\n</febio_spec>\n";
  return EndExport(out);
}
} // namespace cbc3d
