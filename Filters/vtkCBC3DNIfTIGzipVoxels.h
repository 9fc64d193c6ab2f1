#ifndef vtkCBC3DNIfTIGzipVoxels_h
#define vtkCBC3DNIfTIGzipVoxels_h

#include <vtkDataArray.h>
#include <vtkSmartPointer.h>

#include <string>

/// The voxels of a single-file NIfTI-1 image compressed as .nii.gz, inflated in one call of
/// libdeflate (a whole-buffer inflater: label images compress about a thousand to one, and
/// zlib's streaming gzread inflated the shared nidus's 43 MB in 0.10-0.17 s, libdeflate in under
/// 0.01 s). `scalarType` and `voxels` are what vtkNIFTIImageReader read from the header. Returns
/// the voxels in the file's order and the machine's byte order, one component; null where the
/// file is anything else (Analyze, NIfTI-2, several volumes or components, slices stored in
/// reverse (qfac -1), a stream shorter or longer than the header says, or no memory), and then
/// vtkNIFTIImageReader reads it, and reports what is wrong with it.
vtkSmartPointer<vtkDataArray> InflateNIfTIVoxels(const std::string& fileName, int scalarType, vtkIdType voxels);

#endif
