/**
 * @file vtkCBC3DLabelValues.h
 * @brief Label values of VTK arrays, any integer type, and their 32-bit codes (private).
 *
 * The core works on 32-bit labels; images and meshes may hold any 64-bit signed label. These
 * functions read a label array's values exactly, turn them into the core's codes
 * (cbc3d::LabelCodes), and make a label array of the values back from codes.
 */
#ifndef vtkCBC3DLabelValues_h
#define vtkCBC3DLabelValues_h

#include "cbc3d/base/LabelCodes.h"

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

class vtkDataArray;

namespace vtkCBC3DLabelValues
{
// Each of these reads the array on `threads` threads (0: all cores), with the same result for
// any number.

/**
 * Appends the distinct values of a one-component label array to `values`. The array may be of
 * any integer type, or a float type whose values are whole numbers; false with a one-line
 * message for a fraction or a value beyond the 64-bit signed integers (a uint64 above
 * 9223372036854775807).
 */
bool CollectValues(vtkDataArray* array, std::vector<std::int64_t>& values, std::string& error,
  int threads = 1);

/// Writes the code of each value of the array into `out`; false for a value the codes lack.
bool ToCodes(vtkDataArray* array, const cbc3d::LabelCodes& codes, std::int32_t* out);

/**
 * CollectValues over an image of `dimensions` (x fastest) that also finds, in the same pass, the
 * box (inclusive) of the voxels whose value is not `fill`: `upper` is { -1, -1, -1 } when every
 * voxel holds `fill`.
 */
bool CollectImageValues(vtkDataArray* array, const std::array<int, 3>& dimensions, std::int64_t fill,
  std::vector<std::int64_t>& values, std::string& error, std::array<int, 3>& lower, std::array<int, 3>& upper,
  int threads = 1);

/// ToCodes over the box of `size` voxels from `lower` of an image of `dimensions`: the codes of
/// its voxels, x fastest, into `out`.
bool ToCodes(vtkDataArray* array, const cbc3d::LabelCodes& codes, const std::array<int, 3>& dimensions,
  const std::array<int, 3>& lower, const std::array<int, 3>& size, std::int32_t* out, int threads = 1);

/**
 * A label array holding the values of `codes` (`components` per tuple): a vtkIntArray when
 * every value fits in 32 bits, as a label array always was, else a 64-bit integer array
 * (vtkLongArray on Linux, for meshio's legacy .vtk reader).
 */
vtkSmartPointer<vtkDataArray> FromCodes(const std::vector<std::int32_t>& labels,
  const cbc3d::LabelCodes& codes, const char* name, int components = 1);
} // namespace vtkCBC3DLabelValues

#endif
