/**
 * @class   vtkCBC3DMeshQuality
 * @brief   Dihedral angles of a labelled tetrahedral mesh, per tet, per tissue and overall.
 *
 * Input: a vtkUnstructuredGrid of VTK_TETRA cells with an integer `Label` cell array (the
 * output of the other CBC3D filters). The angles are computed here, not with vtkMeshQuality:
 * that filter has no maximum dihedral angle, and in VTK 9.2 its tet "MinAngle" is wrong for
 * slivers.
 *
 * Output: the input mesh plus
 * - cell data `MinDihedralAngle`, `MaxDihedralAngle` (vtkDoubleArray, degrees);
 * - field data, overall: `TetCount` (vtkIdTypeArray, 1 value), `MinDihedralAngle` and
 *   `MaxDihedralAngle` (vtkDoubleArray, degrees, 1 value), `InvertedTetCount` (vtkIdTypeArray);
 * - field data, per tissue, one value per tissue in ascending label order: `TissueLabel`
 *   (vtkIntArray), `TissueTetCount`, `TissueMinDihedralAngle`, `TissueMaxDihedralAngle`,
 *   `TissueInvertedTetCount`.
 *
 * @sa vtkCBC3DBCCLattice
 */
#ifndef vtkCBC3DMeshQuality_h
#define vtkCBC3DMeshQuality_h

#include "vtkCBC3DFiltersModule.h" // For export macro
#include "vtkUnstructuredGridAlgorithm.h"

class VTKCBC3DFILTERS_EXPORT vtkCBC3DMeshQuality : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkCBC3DMeshQuality* New();
  vtkTypeMacro(vtkCBC3DMeshQuality, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Threads for the parallel loops; 0 (the default) uses all cores.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

protected:
  vtkCBC3DMeshQuality() = default;
  ~vtkCBC3DMeshQuality() override = default;

  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int NumberOfThreads = 0;

private:
  vtkCBC3DMeshQuality(const vtkCBC3DMeshQuality&) = delete;
  void operator=(const vtkCBC3DMeshQuality&) = delete;
};

#endif
