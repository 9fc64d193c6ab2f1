#ifndef cbc3d_TaggedMesh_h
#define cbc3d_TaggedMesh_h

#include "cbc3d/base/LabelCodes.h"
#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/Status.h"
#include "cbc3d/base/TetMesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace cbc3d
{
/// A boundary or interface triangle: a face of tet `Tet` (face `Face` of TetTopology.h's
/// TetFaces, VTK order), with its points in that face's outward order. Its normal therefore
/// points out of `Tet`, from the tissue `Sides[0]` into `Sides[1]`.
struct TaggedTriangle
{
  std::array<PointId, 3> Points;
  std::int64_t Tet = -1;
  int Face = 0;
  std::array<std::int32_t, 2> Sides = { 0, 0 };
};

/// A boundary (a tissue against the outside) or an interface (two tissues). `Id` numbers the
/// surfaces 1, 2, ... in the order of TaggedMesh::Surfaces: the formats without names (Medit
/// refs, XDMF facet tags) carry it.
struct TaggedSurface
{
  std::array<std::int32_t, 2> Sides = { 0, 0 };
  bool Boundary = false;
  int Id = 0;
  std::string Name; // boundary_<label> or interface_<a>_<b>
};

/// The mesh every exporter takes: the tets with their tissue labels, and every boundary and
/// interface triangle with the labels on its two sides.
///
/// Conventions (Documentation/Exporting.md):
/// - a boundary triangle has Sides = {tissue, Outside}; its normal points out of the mesh;
/// - an interface triangle has Sides = {a, b} with a < b; its normal points from a into b;
/// - Surfaces: every tissue's boundary in ascending label, then every interface in ascending
///   (a, b); Triangles are grouped by surface in that order.
struct TaggedMesh
{
  std::vector<Eigen::Vector3d> Points;
  std::vector<Tet> Tets;
  std::vector<std::int32_t> Labels;   // one tissue label per tet
  std::vector<std::int32_t> Tissues;  // the distinct labels, ascending
  std::vector<TaggedSurface> Surfaces;
  std::vector<TaggedTriangle> Triangles;
  std::vector<std::size_t> SurfaceStart; // Triangles of surface s: [SurfaceStart[s], SurfaceStart[s + 1])
  std::int32_t Outside = 0;              // the label that stands for the outside
  LabelCodes Codes; // the label values that Labels, Tissues, Sides and Outside stand for
};

/// The value of a label of the mesh, as the writers write it.
inline std::int64_t LabelValue(const TaggedMesh& mesh, std::int32_t label)
{
  return mesh.Codes.ValueOf(label);
}

/// An error naming `format` and `why` when a tissue's value does not fit in 32 bits.
Status RequireInt32Tissues(const TaggedMesh& mesh, const std::string& format, const std::string& why);

/// Builds the tagged mesh of a valid, conforming tet mesh. `outside` stands for the outside on
/// boundary triangles; it must not be a tissue label (an error names the clash), nor may a face
/// have more than two tets. The labels are codes of `codes` (LabelCodes.h), which names use.
Status BuildTaggedMesh(
  const TetMesh& mesh, std::int32_t outside, TaggedMesh& out, const LabelCodes& codes = LabelCodes());
/// The same from the mesh's faces (FindMeshFaces, or SurfaceFaces: faces inside a tissue are
/// ignored), when the caller has them already.
Status BuildTaggedMesh(const TetMesh& mesh, const std::vector<MeshFace>& faces, std::int32_t outside,
  TaggedMesh& out, const LabelCodes& codes = LabelCodes());

/// The index in Surfaces of the surface between `sides` (boundary: {tissue, Outside}), or -1.
int FindSurface(const TaggedMesh& mesh, const std::array<std::int32_t, 2>& sides);

/// The number of tets per tissue, in the order of Tissues.
inline std::vector<std::size_t> TetsPerTissue(const TaggedMesh& mesh)
{
  std::vector<std::size_t> counts(mesh.Tissues.size(), 0);
  for (const std::int32_t label : mesh.Labels)
  {
    const auto at = std::lower_bound(mesh.Tissues.begin(), mesh.Tissues.end(), label);
    ++counts[static_cast<std::size_t>(at - mesh.Tissues.begin())];
  }
  return counts;
}
} // namespace cbc3d

#endif
