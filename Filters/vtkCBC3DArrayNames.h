/**
 * @file vtkCBC3DArrayNames.h
 * @brief The names of every array the CBC3D filters write, in one place.
 *
 * Cell data:
 * - `Label` (vtkIntArray; a 64-bit integer array when a label does not fit 32 bits): the tissue
 *   label of each tet, the label value of the input image unchanged (a tissue labelled 128 in
 *   the image is 128 in the mesh, 5000000000 is 5000000000). `BoundaryLabels`, `FidelityLabel`
 *   and `TissueLabel` follow the same rule.
 * - `MinDihedralAngle`, `MaxDihedralAngle` (vtkDoubleArray, degrees): per tet.
 * - `RefinementLevel` (vtkUnsignedCharArray): red splits between the lattice and the tet.
 *
 * Surface cell data (the tissue surfaces, `cbc3d --surfaces`): `BoundaryLabels` (vtkIntArray, 2
 * components: the tissue behind each triangle, then the label its normal points into: the
 * higher label of an interface, or the outside label on the mesh boundary) and `SurfaceId`
 * (vtkIntArray: 1, 2, ... for the boundaries in ascending label, then the interfaces).
 *
 * Field data (vtkCBC3DBCCLattice): `LatticeEdgeLength` (vtkDoubleArray, mm, 1 value), the
 * lattice cube edge used (the automatic choice when EdgeLength is 0).
 *
 * Point data (vtkCBC3DDeformation): `Displacement` (vtkDoubleArray, 3 components, mm).
 *
 * Over MPI ranks (vtkCBC3DMesher): point data `GlobalIds` (vtkIdTypeArray, the point
 * attribute GLOBALIDS): each point's place in the whole image's lattice, the same on every
 * rank that holds the point; cell data `vtkGhostType` where ghost levels are asked for. Image
 * field data `LatticeBox` (vtkIntArray, 6 values: lower x y z, upper x y z, in the whole image's
 * structured indices): the whole image's tissue box, which a rank's piece frames its lattice on.
 * Field data (vtkCBC3DDeformation): `DeformationIterations`, `DeformationStopReason`,
 * `DeformationSources`, `DeformationTargets`.
 *
 * Field data (vtkCBC3DRefinement): `RefinementPasses`, `RefinementStopReason`,
 * `RefinementBoundaryDistance`, `RefinementBoundaryGap`, `RefinementRelabelledTets`, `RefinementOverlongTets` (tissue tets with
 * an edge beyond their limit, MaximumEdgeLength), and per tissue
 * `FidelityLabel`, `FidelityF1`, `FidelityF2`, `FidelityComponents`, `FidelityComponentsInMesh`.
 *
 * Field data (vtkCBC3DMeshQuality; its class comment says what each holds): over the whole
 * mesh `TetCount`, `InvertedTetCount`, `SmallAngleTetCount`, `LargeAngleTetCount`,
 * `MinDihedralAngle`, `MaxDihedralAngle`, `HausdorffDistance`, `HausdorffDistance95`,
 * `MeanSurfaceDistance`; per tissue in ascending label order `TissueLabel`, `TissueTetCount`,
 * `TissueInvertedTetCount`, `TissueSmallAngleTetCount`, `TissueLargeAngleTetCount`,
 * `TissueMinDihedralAngle`, `TissueMaxDihedralAngle`, `TissueHausdorffDistance`,
 * `TissueMeshToImageDistance`, `TissueImageToMeshDistance`, `TissueHausdorffDistance95`,
 * `TissueMeanSurfaceDistance`, `TissueVolume` (mm^3 in the mesh) and, with an image,
 * `TissueImageVolume` (mm^3 of its voxels).
 *
 * Topology field data (vtkCBC3DMeshQuality, vtkIdTypeArray): over the whole mesh
 * `FaceComponents`, `VertexComponents`, `HingedParts`, `NonManifoldEdges`,
 * `NonManifoldVertices` (these two: the whole body's plus every tissue's), `SurfaceEuler`,
 * `SolverReady` (0 or 1) and, with an image, `ImageSurfaceEuler`, `ImagePinchesJoinedEuler`,
 * `ImagePinchesPartedEuler`; per tissue in ascending label order `TissueFaceComponents`,
 * `TissueVertexComponents`, `TissueHingedParts`, `TissueNonManifoldEdges`,
 * `TissueNonManifoldVertices`, `TissueSurfaceEuler` and, with an image,
 * `TissueImageSurfaceEuler`, `TissueImagePinchesJoinedEuler`, `TissueImagePinchesPartedEuler`.
 */
#ifndef vtkCBC3DArrayNames_h
#define vtkCBC3DArrayNames_h

namespace vtkCBC3DArrayNames
{
constexpr const char* Label = "Label";
constexpr const char* BoundaryLabels = "BoundaryLabels";
constexpr const char* SurfaceId = "SurfaceId";
constexpr const char* MinDihedralAngle = "MinDihedralAngle";
constexpr const char* MaxDihedralAngle = "MaxDihedralAngle";
constexpr const char* LatticeEdgeLength = "LatticeEdgeLength";
constexpr const char* LatticeBox = "LatticeBox";
constexpr const char* GlobalIds = "GlobalIds";
constexpr const char* FixedPoints = "FixedPoints";
constexpr const char* VolumeOffsets = "VolumeOffsets";
constexpr const char* VoxelWindow = "VoxelWindow";
constexpr const char* RefinementLevel = "RefinementLevel";
constexpr const char* RefinementPasses = "RefinementPasses";
constexpr const char* RefinementStopReason = "RefinementStopReason";
constexpr const char* RefinementBoundaryDistance = "RefinementBoundaryDistance";
constexpr const char* RefinementBoundaryGap = "RefinementBoundaryGap";
constexpr const char* RefinementRelabelledTets = "RefinementRelabelledTets";
constexpr const char* RefinementOverlongTets = "RefinementOverlongTets";
constexpr const char* Displacement = "Displacement";
constexpr const char* DeformationIterations = "DeformationIterations";
constexpr const char* DeformationStopReason = "DeformationStopReason";
constexpr const char* DeformationSources = "DeformationSources";
constexpr const char* DeformationTargets = "DeformationTargets";
constexpr const char* FidelityLabel = "FidelityLabel";
constexpr const char* FidelityF1 = "FidelityF1";
constexpr const char* FidelityF2 = "FidelityF2";
constexpr const char* FidelityComponents = "FidelityComponents";
constexpr const char* FidelityComponentsInMesh = "FidelityComponentsInMesh";
constexpr const char* TetCount = "TetCount";
constexpr const char* InvertedTetCount = "InvertedTetCount";
constexpr const char* SmallAngleTetCount = "SmallAngleTetCount";
constexpr const char* LargeAngleTetCount = "LargeAngleTetCount";
constexpr const char* HausdorffDistance = "HausdorffDistance";
constexpr const char* HausdorffDistance95 = "HausdorffDistance95";
constexpr const char* MeanSurfaceDistance = "MeanSurfaceDistance";
constexpr const char* TissueLabel = "TissueLabel";
constexpr const char* TissueSmallAngleTetCount = "TissueSmallAngleTetCount";
constexpr const char* TissueLargeAngleTetCount = "TissueLargeAngleTetCount";
constexpr const char* TissueHausdorffDistance = "TissueHausdorffDistance";
constexpr const char* TissueMeshToImageDistance = "TissueMeshToImageDistance";
constexpr const char* TissueImageToMeshDistance = "TissueImageToMeshDistance";
constexpr const char* TissueHausdorffDistance95 = "TissueHausdorffDistance95";
constexpr const char* TissueMeanSurfaceDistance = "TissueMeanSurfaceDistance";
constexpr const char* TissueVolume = "TissueVolume";
constexpr const char* TissueImageVolume = "TissueImageVolume";
constexpr const char* TissueTetCount = "TissueTetCount";
constexpr const char* TissueMinDihedralAngle = "TissueMinDihedralAngle";
constexpr const char* TissueMaxDihedralAngle = "TissueMaxDihedralAngle";
constexpr const char* TissueInvertedTetCount = "TissueInvertedTetCount";
constexpr const char* FaceComponents = "FaceComponents";
constexpr const char* VertexComponents = "VertexComponents";
constexpr const char* HingedParts = "HingedParts";
constexpr const char* NonManifoldEdges = "NonManifoldEdges";
constexpr const char* NonManifoldVertices = "NonManifoldVertices";
constexpr const char* SurfaceEuler = "SurfaceEuler";
constexpr const char* SolverReady = "SolverReady";
constexpr const char* ImageSurfaceEuler = "ImageSurfaceEuler";
constexpr const char* ImagePinchesJoinedEuler = "ImagePinchesJoinedEuler";
constexpr const char* ImagePinchesPartedEuler = "ImagePinchesPartedEuler";
constexpr const char* TissueFaceComponents = "TissueFaceComponents";
constexpr const char* TissueVertexComponents = "TissueVertexComponents";
constexpr const char* TissueHingedParts = "TissueHingedParts";
constexpr const char* TissueNonManifoldEdges = "TissueNonManifoldEdges";
constexpr const char* TissueNonManifoldVertices = "TissueNonManifoldVertices";
constexpr const char* TissueSurfaceEuler = "TissueSurfaceEuler";
constexpr const char* TissueImageSurfaceEuler = "TissueImageSurfaceEuler";
constexpr const char* TissueImagePinchesJoinedEuler = "TissueImagePinchesJoinedEuler";
constexpr const char* TissueImagePinchesPartedEuler = "TissueImagePinchesPartedEuler";
}

#endif
