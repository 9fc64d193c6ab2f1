#ifndef vtkCBC3DNIfTIGzipVoxels_h
#define vtkCBC3DNIfTIGzipVoxels_h

#include <vtkDataArray.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

/// The voxels of `extent` (within `wholeExtent`, the image's) of a single-file NIfTI-1 image
/// compressed as .nii.gz. `scalarType` and `wholeExtent` are what vtkNIFTIImageReader read from
/// the header. Returns the voxels in the file's order (x fastest) and the machine's byte order,
/// one component; null where the file is anything else (Analyze, NIfTI-2, several volumes or
/// components, slices stored in reverse (qfac -1), a stream shorter than the header says, or no
/// memory), and then vtkNIFTIImageReader reads it, and reports what is wrong with it.
///
/// The whole image is inflated in one call of libdeflate (a whole-buffer inflater: label images
/// compress about a thousand to one, and zlib's streaming gzread inflated the shared nidus's
/// 43 MB in 0.10-0.17 s, libdeflate in under 0.01 s); that path also refuses a stream longer than
/// the header says. A smaller extent is inflated by zlib's stream instead, keeping only the
/// bytes of its slices, so a rank reading a slab of a large image holds about the slab, not the
/// image; the stream past the slab's last slice is not read.
vtkSmartPointer<vtkDataArray> InflateNIfTIVoxels(
  const std::string& fileName, int scalarType, const int wholeExtent[6], const int extent[6]);

/// The boundary voxels (of a value other than the voxel's before them along x, y or z) in each
/// slice of a single-file NIfTI-1 image (.nii or .nii.gz) of `wholeExtent`, along x, then y,
/// then z, into `perSlice`: one pass through zlib's stream, a slice at a time. False, with
/// `perSlice` empty, where InflateNIfTIVoxels would not read the file, or the stream ends short.
bool CountNIfTIBoundaryPerSlice(
  const std::string& fileName, int scalarType, const int wholeExtent[6], std::vector<double>& perSlice);

#endif
