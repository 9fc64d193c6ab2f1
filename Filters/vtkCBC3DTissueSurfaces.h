/**
 * @class   vtkCBC3DTissueSurfaces
 * @brief   The boundary and interface triangles of a labelled tet mesh, with the labels on
 *          their two sides.
 *
 * Input: a vtkUnstructuredGrid of VTK_TETRA cells with an integer `Label` cell array (the
 * output of the other CBC3D filters). Output: a vtkPolyData of every triangle where a tissue
 * meets the outside of the mesh (a boundary) or another tissue (an interface, once), over the
 * points those triangles use, with cell data
 * - `BoundaryLabels` (vtkIntArray, 2 components): the label of the tet behind the triangle, then
 *   the label its normal points into: OutsideLabel on a boundary, the higher label on an
 *   interface (normals point out of the mesh, and from the lower label into the higher);
 * - `SurfaceId` (vtkIntArray): 1, 2, ... over the boundaries in ascending label, then the
 *   interfaces in ascending label pair: the ids the solver formats use
 *   (Documentation/Exporting.md).
 *
 * Threshold `BoundaryLabels` to keep one tissue's surface or one interface.
 *
 * @sa vtkCBC3DMeshWriter
 */
#ifndef vtkCBC3DTissueSurfaces_h
#define vtkCBC3DTissueSurfaces_h

#include "vtkCBC3DFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class VTKCBC3DFILTERS_EXPORT vtkCBC3DTissueSurfaces : public vtkPolyDataAlgorithm
{
public:
  static vtkCBC3DTissueSurfaces* New();
  vtkTypeMacro(vtkCBC3DTissueSurfaces, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The label that stands for the outside on boundary triangles (default 0, the usual
   * background). It must not be a tissue label of the mesh.
   */
  vtkSetMacro(OutsideLabel, vtkTypeInt64);
  vtkGetMacro(OutsideLabel, vtkTypeInt64);
  ///@}

protected:
  vtkCBC3DTissueSurfaces() = default;
  ~vtkCBC3DTissueSurfaces() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  vtkTypeInt64 OutsideLabel = 0;

private:
  vtkCBC3DTissueSurfaces(const vtkCBC3DTissueSurfaces&) = delete;
  void operator=(const vtkCBC3DTissueSurfaces&) = delete;
};

#endif
