/**
 * @file vtkCBC3DConvert.h
 * @brief The only translation between VTK data and the VTK-free cbc3d core (private).
 *
 * Every CBC3D filter reads its label image through ToLabelImage, so all filters accept and
 * reject the same inputs with the same messages.
 */
#ifndef vtkCBC3DConvert_h
#define vtkCBC3DConvert_h

#include "cbc3d/base/LabelCodes.h"
#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/Progress.h"
#include "cbc3d/base/TaggedMesh.h"
#include "cbc3d/base/TetMesh.h"

#include <vtkType.h>

#include <cstdint>
#include <map>
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
 * with one component, of an integer type or a float type whose values are all integers, each a
 * 64-bit signed integer. The core's labels are the codes of `out.Codes` (cbc3d::LabelCodes),
 * made for the image's labels, the background labels and `otherValues` (a mesh's labels, to
 * share one table): the values themselves when all fit in 32 bits. Only the box of the voxels
 * that do not hold the first background label, and one voxel around it, is stored
 * (LabelImage::StoredLower, StoredSize). Returns false with a one-line message for a bad
 * array, or when the image is not 3-D or holds no tissue. The image is read on `threads`
 * threads (0: all cores); the result is the same for any number.
 */
bool ToLabelImage(vtkImageData* image, vtkDataArray* labels,
  const std::vector<vtkTypeInt64>& backgroundLabels, cbc3d::LabelImage& out, std::string& error,
  std::vector<std::int64_t> otherValues = {}, int threads = 1);

/**
 * Per-tissue settings given by label value (`byValue`) as settings by the image's label codes;
 * false with a one-line message naming a label the image cannot hold or a background label.
 */
bool ToTissueCodes(const std::map<long long, double>& byValue, const cbc3d::LabelImage& image,
  std::map<std::int32_t, double>& byCode, std::string& error);

/// Appends the distinct values of the grid's `Label` cell array; false with a one-line message.
bool MeshLabelValues(vtkUnstructuredGrid* grid, std::vector<std::int64_t>& values, std::string& error);

/**
 * Copies a tetrahedral grid with a `Label` cell array into the core mesh, labels as codes of
 * `codes` (by default the values themselves, which must then fit in 32 bits). Returns false
 * with a one-line message when a cell is not a VTK_TETRA, the Label array is missing, or a
 * label has no code.
 */
bool FromUnstructuredGrid(vtkUnstructuredGrid* grid, cbc3d::TetMesh& out, std::string& error,
  const cbc3d::LabelCodes& codes = cbc3d::LabelCodes());

/**
 * The tagged mesh of a tetrahedral grid with a `Label` cell array (FromUnstructuredGrid, then
 * cbc3d::BuildTaggedMesh with `outside` standing for the outside), its labels any 64-bit
 * values (TaggedMesh::Codes); false with a one-line message.
 */
bool ToTaggedMesh(vtkUnstructuredGrid* grid, vtkTypeInt64 outside, cbc3d::TaggedMesh& out, std::string& error);

/**
 * Fills `out` with the mesh's points, VTK_TETRA cells and the `Label` cell array: the values of
 * the mesh's codes, a vtkIntArray when they fit in 32 bits, else a 64-bit integer array.
 */
void ToUnstructuredGrid(const cbc3d::TetMesh& mesh, const cbc3d::LabelCodes& codes, vtkUnstructuredGrid* out);

/**
 * Fills `out` with the tagged mesh's boundary and interface triangles over the points they use:
 * cell data `BoundaryLabels` (2 components: the label behind each triangle, then the label its
 * normal points into, TaggedMesh's rule; a vtkIntArray, or a 64-bit one for larger labels) and
 * `SurfaceId` (TaggedSurface::Id).
 */
void ToPolyData(const cbc3d::TaggedMesh& mesh, vtkPolyData* out);

/// A core progress callback that drives the algorithm's progress and reports its abort flag.
cbc3d::Progress MakeProgress(vtkAlgorithm* algorithm);
} // namespace vtkCBC3DConvert

#endif
