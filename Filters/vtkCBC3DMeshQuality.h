/**
 * @class   vtkCBC3DMeshQuality
 * @brief   Dihedral angles, topology and, with the label image, the Hausdorff distance of a
 *          labelled mesh.
 *
 * Input port 0: a vtkUnstructuredGrid of VTK_TETRA cells with an integer `Label` cell array (the
 * output of the other CBC3D filters). Input port 1 (optional): the label image the mesh was made
 * from (its label array is input array 0; background labels as in the other filters).
 *
 * The dihedral angles are computed here, not with vtkMeshQuality: that filter has no maximum
 * dihedral angle, and in VTK 9.2 its tet "MinAngle" is wrong for some slivers.
 *
 * With the image, each tissue's fidelity is measured as in the CBC3D paper: between the tissue's
 * surface vertices (vertices of mesh faces that belong to exactly one tet of the tissue) and the
 * centres of its boundary voxels (voxels of the tissue with a face-neighbour outside it, the
 * image border counting as outside), in the image's physical frame (mm). Nearest points are
 * found with vtkStaticPointLocator.
 *
 * Output: the input mesh plus
 * - cell data `MinDihedralAngle`, `MaxDihedralAngle` (vtkDoubleArray, degrees);
 * - field data over the whole mesh (one value each): `TetCount`, `InvertedTetCount`,
 *   `SmallAngleTetCount` (tets with an angle under 10 degrees), `LargeAngleTetCount` (over 170
 *   degrees) (vtkIdTypeArray); `MinDihedralAngle`, `MaxDihedralAngle` (vtkDoubleArray, degrees);
 *   with the image, `HausdorffDistance` (the maximum over tissues), `HausdorffDistance95` and
 *   `MeanSurfaceDistance` (over all tissues' surface samples together) (mm);
 * - field data per tissue, one value per tissue in ascending label order: `TissueLabel`
 *   (vtkIntArray), `TissueTetCount`, `TissueInvertedTetCount`, `TissueSmallAngleTetCount`,
 *   `TissueLargeAngleTetCount`, `TissueMinDihedralAngle`, `TissueMaxDihedralAngle`,
 *   `TissueVolume` (mm^3 of its tets); with the image, `TissueImageVolume` (mm^3 of its voxels:
 *   a mesh through the boundary voxels' centres is smaller by about half a voxel of depth over
 *   the tissue's surface), `TissueHausdorffDistance`, `TissueMeshToImageDistance` and
 *   `TissueImageToMeshDistance` (the two one-sided distances), `TissueHausdorffDistance95` (the
 *   larger of the two one-sided 95th percentiles) and `TissueMeanSurfaceDistance` (mm).
 *
 * Topology (field data, vtkIdTypeArray, cbc3d/quality/MeshTopology.h): a tissue's tets are those with
 * its label, its surface the mesh faces with exactly one tet of it (interfaces are in both
 * tissues' surfaces); the whole body is every tet, its surface the mesh boundary.
 * - over the whole body: `FaceComponents` and `VertexComponents` (its tets connected through
 *   faces, through vertices), `HingedParts` (the difference: parts held by an edge or a vertex
 *   only), `SurfaceEuler` (V - E + F of its surface); `NonManifoldEdges` (surface edges in more
 *   than two surface triangles) and `NonManifoldVertices` (surface vertices whose triangles form
 *   more than one fan), each the whole body's plus the sum over tissues, so that the mesh
 *   counts every defect a solver would meet; `SolverReady` (1 when the body and every tissue
 *   have no hinged part and no non-manifold edge or vertex, else 0); with the image,
 *   `ImageSurfaceEuler` (V - E + F of the voxel-face surface of all tissue voxels), and
 *   `ImagePinchesJoinedEuler` and `ImagePinchesPartedEuler`: what a manifold surface round the
 *   same voxels has where every pinch (voxels touching only along an edge or at a corner) is
 *   joined, or parted; the voxel-face figure is their mean (cbc3d::ImageTopology);
 * - per tissue (the rows above): `TissueFaceComponents`, `TissueVertexComponents`,
 *   `TissueHingedParts`, `TissueNonManifoldEdges`, `TissueNonManifoldVertices`,
 *   `TissueSurfaceEuler` and, with the image, `TissueImageSurfaceEuler`,
 *   `TissueImagePinchesJoinedEuler` and `TissueImagePinchesPartedEuler` (its voxels'). A tissue
 *   absent from the mesh has 0 components and Euler 0 (the empty surface's).
 * Equal mesh and image Euler characteristics per tissue with a solver-ready mesh mean the
 * surfaces have the image's topology (a ball 2, a torus 0, a hollow shell 4).
 *
 * A tissue present in only one of mesh and image gets NaN distances and a warning; the mesh's
 * distances are then NaN too (a lost tissue has no finite distance).
 *
 * @sa vtkCBC3DBCCLattice
 */
#ifndef vtkCBC3DMeshQuality_h
#define vtkCBC3DMeshQuality_h

#include "vtkCBC3DAlgorithm.h"
#include "vtkCBC3DFiltersModule.h" // For export macro

class VTKCBC3DFILTERS_EXPORT vtkCBC3DMeshQuality : public vtkCBC3DAlgorithm
{
public:
  static vtkCBC3DMeshQuality* New();
  vtkTypeMacro(vtkCBC3DMeshQuality, vtkCBC3DAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkCBC3DMeshQuality();
  ~vtkCBC3DMeshQuality() override = default;

  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkCBC3DMeshQuality(const vtkCBC3DMeshQuality&) = delete;
  void operator=(const vtkCBC3DMeshQuality&) = delete;
};

#endif
