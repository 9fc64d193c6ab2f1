/**
 * @file vtkCBC3DArrayNames.h
 * @brief The names of every array the CBC3D filters write, in one place.
 *
 * Cell data:
 * - `Label` (vtkIntArray): the tissue label of each tet, the label value of the input image
 *   unchanged (a tissue labelled 128 in the image is 128 in the mesh).
 */
#ifndef vtkCBC3DArrayNames_h
#define vtkCBC3DArrayNames_h

namespace vtkCBC3DArrayNames
{
constexpr const char* Label = "Label";
}

#endif
