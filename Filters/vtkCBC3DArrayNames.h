/**
 * @file vtkCBC3DArrayNames.h
 * @brief The names of every array the CBC3D filters write, in one place.
 *
 * Cell data:
 * - `Label` (vtkIntArray): the tissue label of each tet, the label value of the input image
 *   unchanged (a tissue labelled 128 in the image is 128 in the mesh).
 * - `MinDihedralAngle`, `MaxDihedralAngle` (vtkDoubleArray, degrees): per tet.
 *
 * Field data (vtkCBC3DBCCLattice): `LatticeEdgeLength` (vtkDoubleArray, mm, 1 value), the
 * lattice cube edge used (the automatic choice when EdgeLength is 0).
 *
 * Field data (vtkCBC3DMeshQuality): `TetCount`, `MinDihedralAngle`, `MaxDihedralAngle`,
 * `InvertedTetCount` (one value each, over the whole mesh), and per tissue in ascending label
 * order `TissueLabel`, `TissueTetCount`, `TissueMinDihedralAngle`, `TissueMaxDihedralAngle`,
 * `TissueInvertedTetCount`.
 */
#ifndef vtkCBC3DArrayNames_h
#define vtkCBC3DArrayNames_h

namespace vtkCBC3DArrayNames
{
constexpr const char* Label = "Label";
constexpr const char* MinDihedralAngle = "MinDihedralAngle";
constexpr const char* MaxDihedralAngle = "MaxDihedralAngle";
constexpr const char* LatticeEdgeLength = "LatticeEdgeLength";
constexpr const char* TetCount = "TetCount";
constexpr const char* InvertedTetCount = "InvertedTetCount";
constexpr const char* TissueLabel = "TissueLabel";
constexpr const char* TissueTetCount = "TissueTetCount";
constexpr const char* TissueMinDihedralAngle = "TissueMinDihedralAngle";
constexpr const char* TissueMaxDihedralAngle = "TissueMaxDihedralAngle";
constexpr const char* TissueInvertedTetCount = "TissueInvertedTetCount";
}

#endif
