/**
 * @class   vtkCBC3DLabelImageCache
 * @brief   The core's view of the last label image read, shared by the filters that read it.
 *
 * A pipeline hands one image to every CBC3D stage (lattice, refinement, deformation, quality),
 * and each stage needs the same int32 copy of its labels. Converting it once per stage cost a
 * quarter of the run on a large, mostly empty image (every conversion allocated, faulted in and
 * filled a whole-image array; a conversion now stores only the box of the voxels other than the
 * first background label, and one voxel around it: cbc3d::LabelImage). The cache keeps the last
 * conversion, keyed by the label array, its and the image's modification times and the
 * background labels; a changed input or setting misses and converts again. One entry, so it
 * holds at most one image.
 */
#ifndef vtkCBC3DLabelImageCache_h
#define vtkCBC3DLabelImageCache_h

#include <vtkType.h> // For vtkTypeInt64

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;
namespace cbc3d
{
struct LabelImage;
}

namespace vtkCBC3DLabelImageCache
{
/// The label image of `image`'s array `labels` with these background labels, its codes able to
/// stand for `otherValues` too (a mesh's labels): the cached one when nothing changed since it
/// was converted and its codes cover those values (codes keep the values' order, so any table
/// that covers them gives the same mesh). Null, with `error` set, for unusable input. A
/// conversion reads the image on `threads` threads (0: all cores).
std::shared_ptr<const cbc3d::LabelImage> Get(vtkImageData* image, vtkDataArray* labels,
  const std::vector<vtkTypeInt64>& backgroundLabels, const std::vector<std::int64_t>& otherValues,
  std::string& error, int threads = 1);
}

#endif
