/**
 * @class   vtkCBC3DAlgorithm
 * @brief   Base of the CBC3D filters: background labels, threads, and label-image input.
 *
 * Every CBC3D filter produces a vtkUnstructuredGrid and reads a label image the same way: the
 * image's label array is input array 0 (SetInputArrayToProcess; default: the active point
 * scalars), every label not listed as background is a tissue, and label values are kept as
 * they are. Subclasses say on which input port the image arrives.
 *
 * @sa vtkCBC3DBCCLattice vtkCBC3DMeshQuality
 */
#ifndef vtkCBC3DAlgorithm_h
#define vtkCBC3DAlgorithm_h

#include "vtkCBC3DFiltersModule.h" // For export macro
#include "vtkUnstructuredGridAlgorithm.h"

#include <vector> // For background labels

namespace cbc3d
{
struct LabelImage;
}

class VTKCBC3DFILTERS_EXPORT vtkCBC3DAlgorithm : public vtkUnstructuredGridAlgorithm
{
public:
  vtkTypeMacro(vtkCBC3DAlgorithm, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Labels that are not tissue. Default: the single label 0.
   */
  void AddBackgroundLabel(int label);
  void RemoveAllBackgroundLabels();
  void SetBackgroundLabel(int label);
  int GetNumberOfBackgroundLabels() const;
  int GetBackgroundLabel(int index) const;
  ///@}

  ///@{
  /**
   * Threads for the parallel loops; 0 (the default) uses all cores.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

protected:
  /// `imagePort`: the input port of the label image; input array 0 is set to its point scalars.
  explicit vtkCBC3DAlgorithm(int imagePort = 0);
  ~vtkCBC3DAlgorithm() override = default;

  /**
   * Reads the label image on its port into the core's view. On failure reports the problem
   * with vtkErrorMacro and returns false.
   */
  bool ReadLabelImage(vtkInformationVector** inputVector, cbc3d::LabelImage& image);

  int ImagePort;
  std::vector<int> BackgroundLabels = { 0 };
  int NumberOfThreads = 0;

private:
  vtkCBC3DAlgorithm(const vtkCBC3DAlgorithm&) = delete;
  void operator=(const vtkCBC3DAlgorithm&) = delete;
};

#endif
