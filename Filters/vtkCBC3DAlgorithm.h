/**
 * @class   vtkCBC3DAlgorithm
 * @brief   Base of the CBC3D filters: background labels, threads, and label-image input.
 *
 * Every CBC3D filter produces a vtkUnstructuredGrid and reads a label image the same way: the
 * image's label array is input array 0 (SetInputArrayToProcess; default: the active point
 * scalars), every label not listed as background is a tissue, and label values are kept as
 * they are. The image arrives on port 0 (filters that start from the image) or on port 1 after
 * a mesh on port 0 (filters that work on a mesh); subclasses say which.
 *
 * @sa vtkCBC3DBCCLattice vtkCBC3DMeshQuality
 */
#ifndef vtkCBC3DAlgorithm_h
#define vtkCBC3DAlgorithm_h

#include "vtkCBC3DFiltersModule.h" // For export macro
#include "vtkUnstructuredGridAlgorithm.h"

#include <cstdint> // For label codes
#include <map>     // For the settings of single tissues
#include <memory>  // For the shared label image
#include <vector>  // For background labels

class vtkImageData;

class vtkUnstructuredGrid;

namespace cbc3d
{
class LabelCodes;
class Status;
struct EdgeLengthLimits;
struct LabelImage;
struct TetMesh;
}

class VTKCBC3DFILTERS_EXPORT vtkCBC3DAlgorithm : public vtkUnstructuredGridAlgorithm
{
public:
  vtkTypeMacro(vtkCBC3DAlgorithm, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Labels that are not tissue, any 64-bit values. Default: the single label 0.
   */
  void AddBackgroundLabel(vtkTypeInt64 label);
  void RemoveAllBackgroundLabels();
  void SetBackgroundLabel(vtkTypeInt64 label);
  int GetNumberOfBackgroundLabels() const;
  vtkTypeInt64 GetBackgroundLabel(int index) const;
  ///@}

  ///@{
  /**
   * Threads for the parallel loops; 0 (the default) uses all cores.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Edge limits in mm, for the filters that make or move edges (Refinement, Deformation and
   * the one-shot Mesher; the other stages ignore them): no tet of a tissue keeps an edge longer
   * than MaximumEdgeLength (0, the default: no limit), or than its tissue's own limit, given by
   * label value. A label the image lacks, or a background label, fails the run with an error
   * naming it.
   */
  vtkSetMacro(MaximumEdgeLength, double);
  vtkGetMacro(MaximumEdgeLength, double);
  void SetTissueMaximumEdgeLength(double label, double length);
  void RemoveAllTissueMaximumEdgeLengths();
  ///@}

  ///@{
  /**
   * Fidelity targets of single tissues, given by label value, in place of Fidelity, for
   * Refinement and the one-shot Mesher (the other stages ignore them). A label the image lacks,
   * or a background label, fails the run with an error naming it.
   */
  void SetTissueFidelity(double label, double fidelity);
  void RemoveAllTissueFidelities();
  ///@}

  ///@{
  /**
   * A tet budget (0, the default: none), for the lattice (whose automatic size grows so that it
   * holds at most about a quarter of it), refinement (which keeps the splits that fit, those that
   * gain the most fidelity first) and the one-shot Mesher.
   */
  vtkSetClampMacro(MaximumNumberOfTets, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfTets, vtkIdType);
  ///@}

  ///@{
  /**
   * The label image, for filters that take a mesh on port 0 and the image on port 1.
   */
  void SetImageConnection(vtkAlgorithmOutput* output);
  void SetImageData(vtkImageData* image);
  ///@}

protected:
  enum class ImageInput
  {
    Port0,         // image in, mesh out
    Port1,         // mesh on port 0, image on port 1
    OptionalPort1  // the same, the image optional
  };
  /// Sets the ports and makes input array 0 the image's active point scalars.
  explicit vtkCBC3DAlgorithm(ImageInput input = ImageInput::Port0);

  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// Whether an image was connected (always true for ImageInput::Port0).
  bool HasImage(vtkInformationVector** inputVector) const;
  ~vtkCBC3DAlgorithm() override = default;

  /**
   * Keeps the image's voxel spacing from the pipeline information, known before any voxel is
   * read, so that the ParaView panel can show the sizes that 0 stands for (the subclasses'
   * GetAutomatic... getters).
   */
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  ///@{
  /// The automatic lattice edge and minimum edge length, as the core computes them from the
  /// spacing of the last RequestInformation; 0 while that spacing is unknown.
  double AutomaticLatticeEdge() const;
  double AutomaticMinimumEdge() const;
  ///@}

  /**
   * The core's view of the label image on its port, its labels coded by image.Codes, which
   * can also code `otherValues` (a mesh's labels); shared with the other stages that read the
   * same image (vtkCBC3DLabelImageCache). On failure reports the problem with vtkErrorMacro
   * and returns null.
   */
  std::shared_ptr<const cbc3d::LabelImage> ReadLabelImage(
    vtkInformationVector** inputVector, const std::vector<std::int64_t>& otherValues = {});

  /**
   * Reads the labelled tet mesh on port 0 (filters whose image is on port 1), its labels
   * coded by `codes`, made for them and the background labels. On failure reports the problem
   * with vtkErrorMacro and returns false.
   */
  bool ReadMesh(vtkInformationVector** inputVector, cbc3d::TetMesh& mesh, cbc3d::LabelCodes& codes);

  /**
   * The end of RequestData when a core function did not succeed: a stop asked by the user
   * leaves an empty output and is no error (returns 1); anything else is reported with
   * vtkErrorMacro (returns 0).
   */
  int EndOnFailure(const cbc3d::Status& status, vtkUnstructuredGrid* output);

  /**
   * The mesh on port 0 and the image on port 1, their labels coded by one table (image->Codes):
   * the inputs of the filters that refine, move or measure a mesh against its image.
   */
  bool ReadMeshAndImage(vtkInformationVector** inputVector, cbc3d::TetMesh& mesh,
    std::shared_ptr<const cbc3d::LabelImage>& image);

  int ImagePort;
  bool ImageOptional;
  /// Settings by label value as settings by the image's label codes; false, with vtkErrorMacro,
  /// for a label the image lacks or a background label.
  bool ReadTissueCodes(const std::map<long long, double>& byValue, const cbc3d::LabelImage& image,
    std::map<std::int32_t, double>& byCode);
  /// The edge limits by the image's label codes (ReadTissueCodes).
  bool ReadEdgeLimits(const cbc3d::LabelImage& image, cbc3d::EdgeLengthLimits& limits);
  /// Gives `stage` this filter's edge limits, tissue fidelities and tet budget.
  void CopySizeControlsTo(vtkCBC3DAlgorithm* stage) const;
  /// Whether an edge limit or a tissue's fidelity above 0 asks for refinement.
  bool SizeControlsAskForRefinement() const;

  double InformationSpacing[3] = { 0.0, 0.0, 0.0 };
  std::vector<vtkTypeInt64> BackgroundLabels = { 0 };
  int NumberOfThreads = 0;
  double MaximumEdgeLength = 0.0;
  std::map<long long, double> TissueMaximumEdgeLength; // label value -> mm
  std::map<long long, double> TissueFidelity;          // label value -> F
  vtkIdType MaximumNumberOfTets = 0;

private:
  /// The per-tissue setters' one body: the value of `label` in `values`, then Modified.
  void SetTissueValue(std::map<long long, double>& values, double label, double value);
  void ClearTissueValues(std::map<long long, double>& values);

  vtkCBC3DAlgorithm(const vtkCBC3DAlgorithm&) = delete;
  void operator=(const vtkCBC3DAlgorithm&) = delete;
};

#endif
