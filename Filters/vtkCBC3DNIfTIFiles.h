#ifndef vtkCBC3DNIfTIFiles_h
#define vtkCBC3DNIfTIFiles_h

#include <string>

class vtkMatrix4x4;

/// The NIfTI reader's look at the files before VTK's reader does: which file holds the voxels,
/// which the header, and what is wrong with a header that VTK's reader would misread.
namespace vtkCBC3DNIfTIFiles
{
/// Largest deviation of a matrix's 3x3 part M from orthonormality: max |M^T M - I|.
double OrthonormalityError(vtkMatrix4x4* m);

/// The file that holds the voxels: the .img (.img.gz) beside an Analyze/NIfTI .hdr, otherwise
/// the file itself. Empty when a .hdr has no such file (the inner reader then says so).
std::string VoxelFileName(const std::string& fileName);

/// The header file of a .hdr/.img pair given by its .img, otherwise the file itself.
std::string HeaderFileName(const std::string& fileName);

/// What is wrong with the header's sizeof_hdr or datatype fields, in words; empty when both are
/// sound or the file is too short to tell (vtkNIFTIImageReader then says why it cannot read it).
std::string HeaderProblem(const std::string& headerFile);
} // namespace vtkCBC3DNIfTIFiles

#endif
