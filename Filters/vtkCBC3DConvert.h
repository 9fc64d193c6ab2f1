/**
 * @file vtkCBC3DConvert.h
 * @brief The only translation between VTK data and the VTK-free cbc3d core (private).
 *
 * Every CBC3D filter reads its label image through ToLabelImage, so all filters accept and
 * reject the same inputs with the same messages.
 */
#ifndef vtkCBC3DConvert_h
#define vtkCBC3DConvert_h

#include "cbc3d/LabelImage.h"
#include "cbc3d/Progress.h"
#include "cbc3d/TaggedMesh.h"
#include "cbc3d/TetMesh.h"

#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataArray;
class vtkImageData;
class vtkInformation;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace vtkCBC3DConvert
{
/**
 * The label array an algorithm was asked for, looked up on the label image whatever input port
 * the request names (ParaView's array properties always say port 0). `arrayRequest` is the
 * algorithm's GetInputArrayInformation(0): a chosen name gives that point array (null if
 * missing, never another array); no name (ParaView sends an empty one while the input's arrays
 * are not yet known) gives the active point scalars, else the image's only point array.
 */
vtkDataArray* ChooseLabelArray(vtkInformation* arrayRequest, vtkImageData* image);

/**
 * Copies a label image into the core's frame and label storage. The array must be point data
 * with one component, of an integer type or a float type whose values are all integers, and
 * every value must fit in 32 bits. Returns false with a one-line message otherwise, or when the
 * image is not 3-D or holds no tissue.
 */
bool ToLabelImage(vtkImageData* image, vtkDataArray* labels,
  const std::vector<int>& backgroundLabels, cbc3d::LabelImage& out, std::string& error);

/**
 * Copies a tetrahedral grid with a `Label` cell array into the core mesh. Returns false with a
 * one-line message when a cell is not a VTK_TETRA or the Label array is missing.
 */
bool FromUnstructuredGrid(vtkUnstructuredGrid* grid, cbc3d::TetMesh& out, std::string& error);

/**
 * The tagged mesh of a tetrahedral grid with a `Label` cell array (FromUnstructuredGrid, then
 * cbc3d::BuildTaggedMesh with `outside` standing for the outside); false with a one-line message.
 */
bool ToTaggedMesh(vtkUnstructuredGrid* grid, std::int32_t outside, cbc3d::TaggedMesh& out, std::string& error);

/// Fills `out` with the mesh's points, VTK_TETRA cells and the `Label` cell array.
void ToUnstructuredGrid(const cbc3d::TetMesh& mesh, vtkUnstructuredGrid* out);

/**
 * Fills `out` with the tagged mesh's boundary and interface triangles over the points they use:
 * cell data `BoundaryLabels` (vtkIntArray, 2 components: the label behind each triangle, then
 * the label its normal points into; TaggedMesh's rule) and `SurfaceId` (TaggedSurface::Id).
 */
void ToPolyData(const cbc3d::TaggedMesh& mesh, vtkPolyData* out);

/// A core progress callback that drives the algorithm's progress and reports its abort flag.
cbc3d::Progress MakeProgress(vtkAlgorithm* algorithm);
} // namespace vtkCBC3DConvert

#endif
