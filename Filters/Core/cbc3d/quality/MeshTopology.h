#ifndef cbc3d_MeshTopology_h
#define cbc3d_MeshTopology_h

#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/quality/ImageTopology.h" // the image's side of the comparison

#include <cstdint>
#include <map>

namespace cbc3d
{
/// Topology of one set of tets (a tissue, or the whole mesh) and of its boundary surface.
struct RegionTopology
{
  std::int64_t FaceComponents = 0;      // its tets, connected through shared faces
  std::int64_t VertexComponents = 0;    // its tets, connected through shared vertices
  std::int64_t HingedParts = 0;         // FaceComponents - VertexComponents
  std::int64_t SurfaceTriangles = 0;    // mesh faces with exactly one tet of the set
  std::int64_t NonManifoldEdges = 0;    // surface edges in more than two surface triangles
  std::int64_t NonManifoldVertices = 0; // surface vertices whose triangles form several fans
  std::int64_t SurfaceEuler = 0;        // V - E + F of the surface triangles

  /// No hinged part, no non-manifold edge or vertex.
  bool Manifold() const
  {
    return this->HingedParts == 0 && this->NonManifoldEdges == 0 && this->NonManifoldVertices == 0;
  }
};

/// The topology of a labelled mesh: the whole body (every tet) and each tissue.
struct MeshTopology
{
  RegionTopology Whole;
  std::map<std::int32_t, RegionTopology> Tissues; // keyed by label value

  /// What a finite-element solver needs: no hinge and a manifold surface, for the whole body
  /// and for every tissue.
  bool SolverReady() const;
};

/// Measures the whole body and every tissue of `mesh`.
///
/// A tissue's tets are those with its label; its surface is the mesh faces with exactly one tet
/// of the tissue, so an interface between two tissues is in both surfaces and the mesh boundary
/// is in the surface of the tissue inside it. The whole body's surface is the mesh boundary.
/// A surface vertex is non-manifold when its surface triangles form more than one fan, two
/// triangles at the vertex being in one fan when they share an edge through it. Linear time
/// (bucketing on vertices); faces of more than two tets (a non-conforming mesh) count only
/// their first two tets.
MeshTopology MeasureMeshTopology(const TetMesh& mesh, int numberOfThreads = 1);
/// The same from the mesh's faces (FindMeshFaces), when the caller has them already. The
/// surfaces' edges and vertices are counted on `numberOfThreads` (0: all cores): the same counts.
MeshTopology MeasureMeshTopology(const TetMesh& mesh, const std::vector<MeshFace>& faces, int numberOfThreads = 1);
} // namespace cbc3d

#endif
