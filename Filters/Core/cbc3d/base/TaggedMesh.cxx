#include "cbc3d/base/TaggedMesh.h"

#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/TetTopology.h"

#include <algorithm>
#include <tuple>

namespace cbc3d
{
namespace
{
// The TetFaces index of the face of `tet` over `face`'s points: the face without the one
// vertex of the tet that the face lacks (TetFaces omits 2, 0, 1, 3 in turn).
int FaceIndex(const Tet& tet, const std::array<PointId, 3>& face)
{
  constexpr std::array<int, 4> faceWithout = { 1, 2, 0, 3 };
  for (int v = 0; v < 4; ++v)
  {
    if (std::find(face.begin(), face.end(), tet[v]) == face.end())
    {
      return faceWithout[v];
    }
  }
  return -1;
}

TaggedTriangle MakeTriangle(const TetMesh& mesh, std::int64_t tet, const MeshFace& face,
  std::int32_t otherSide)
{
  TaggedTriangle triangle;
  triangle.Tet = tet;
  triangle.Face = FaceIndex(mesh.Tets[tet], face.Points);
  for (int k = 0; k < 3; ++k)
  {
    triangle.Points[k] = mesh.Tets[tet][TetFaces[triangle.Face][k]];
  }
  triangle.Sides = { mesh.Labels[tet], otherSide };
  return triangle;
}

std::string SurfaceName(const TaggedSurface& surface, const LabelCodes& codes)
{
  const std::string first = std::to_string(codes.ValueOf(surface.Sides[0]));
  return surface.Boundary ? "boundary_" + first
                          : "interface_" + first + "_" + std::to_string(codes.ValueOf(surface.Sides[1]));
}

// Sorts the triangles into surfaces (boundaries first, then interfaces, each ascending) and
// numbers the surfaces.
void GroupSurfaces(TaggedMesh& out)
{
  auto key = [&](const TaggedTriangle& t) {
    return std::make_tuple(t.Sides[1] != out.Outside, t.Sides[0], t.Sides[1]);
  };
  std::stable_sort(out.Triangles.begin(), out.Triangles.end(),
    [&](const TaggedTriangle& a, const TaggedTriangle& b) { return key(a) < key(b); });
  out.Surfaces.clear();
  out.SurfaceStart.clear();
  for (std::size_t i = 0; i < out.Triangles.size(); ++i)
  {
    if (i == 0 || key(out.Triangles[i]) != key(out.Triangles[i - 1]))
    {
      TaggedSurface surface;
      surface.Sides = out.Triangles[i].Sides;
      surface.Boundary = surface.Sides[1] == out.Outside;
      surface.Id = static_cast<int>(out.Surfaces.size()) + 1;
      surface.Name = SurfaceName(surface, out.Codes);
      out.Surfaces.push_back(surface);
      out.SurfaceStart.push_back(i);
    }
  }
  out.SurfaceStart.push_back(out.Triangles.size());
}

Status TagValidMesh(const TetMesh& mesh, const std::vector<MeshFace>& faces, std::int32_t outside,
  TaggedMesh& out, const LabelCodes& codes)
{
  out = TaggedMesh();
  out.Points = mesh.Points;
  out.Tets = mesh.Tets;
  out.Labels = mesh.Labels;
  out.Outside = outside;
  out.Codes = codes;
  out.Tissues = mesh.Labels;
  std::sort(out.Tissues.begin(), out.Tissues.end());
  out.Tissues.erase(std::unique(out.Tissues.begin(), out.Tissues.end()), out.Tissues.end());
  if (std::binary_search(out.Tissues.begin(), out.Tissues.end(), outside))
  {
    return Status::Error("the outside label " + std::to_string(codes.ValueOf(outside)) +
      " is also a tissue label: choose another for the surfaces' outside");
  }
  for (const MeshFace& face : faces)
  {
    if (face.TetCount > 2)
    {
      return Status::Error("the mesh does not conform: a face has more than two tets");
    }
    if (face.TetCount == 1)
    {
      out.Triangles.push_back(MakeTriangle(mesh, face.Tets[0], face, outside));
      continue;
    }
    std::int64_t low = face.Tets[0];
    std::int64_t high = face.Tets[1];
    if (mesh.Labels[low] == mesh.Labels[high])
    {
      continue; // inside a tissue
    }
    if (mesh.Labels[low] > mesh.Labels[high])
    {
      std::swap(low, high);
    }
    out.Triangles.push_back(MakeTriangle(mesh, low, face, mesh.Labels[high]));
  }
  GroupSurfaces(out);
  return Status::Ok();
}
} // namespace

Status BuildTaggedMesh(
  const TetMesh& mesh, std::int32_t outside, TaggedMesh& out, const LabelCodes& codes)
{
  const Status valid = ValidateTetMesh(mesh);
  return valid.IsOk() ? TagValidMesh(mesh, FindMeshFaces(mesh), outside, out, codes) : valid;
}

Status BuildTaggedMesh(const TetMesh& mesh, const std::vector<MeshFace>& faces, std::int32_t outside,
  TaggedMesh& out, const LabelCodes& codes)
{
  const Status valid = ValidateTetMesh(mesh);
  return valid.IsOk() ? TagValidMesh(mesh, faces, outside, out, codes) : valid;
}

Status RequireInt32Tissues(const TaggedMesh& mesh, const std::string& format, const std::string& why)
{
  for (const std::int32_t tissue : mesh.Tissues)
  {
    const std::int64_t value = LabelValue(mesh, tissue);
    if (!FitsInt32(value))
    {
      return Status::Error(format + " cannot hold tissue label " + std::to_string(value) + ": " + why +
        " (.vtu, .vtk, .inp, .feb and .exo keep any label)");
    }
  }
  return Status::Ok();
}

int FindSurface(const TaggedMesh& mesh, const std::array<std::int32_t, 2>& sides)
{
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
  {
    if (mesh.Surfaces[s].Sides == sides)
    {
      return static_cast<int>(s);
    }
  }
  return -1;
}
} // namespace cbc3d
