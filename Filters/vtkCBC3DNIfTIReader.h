/**
 * @class   vtkCBC3DNIfTIReader
 * @brief   Read a NIfTI-1/2 image (.nii, .nii.gz) into its world frame (RAS millimetres).
 *
 * The voxels are read by VTK's vtkNIFTIImageReader; this class then places the image where the
 * NIfTI header says it lies, by setting the output's origin, spacing and direction matrix so
 * that vtkImageData::TransformIndexToPhysicalPoint gives every voxel's NIfTI world position
 * (x = right, y = anterior, z = superior, in millimetres). The header's transforms are used in
 * the order the NIfTI standard recommends:
 *
 * - "sform" when sform_code > 0 and the sform, with the voxel size divided out, is a rotation
 *   or a reflection (orthonormal within 1e-4);
 * - "qform" when sform_code is 0, or the sform holds a shear or a scaling (then with a
 *   warning), and qform_code > 0;
 * - "voxel size" when neither code is set: origin 0, identity direction, spacing pixdim.
 *
 * GetFrameSource() tells which rule was applied to the last file read. An sform that holds a
 * shear or a scaling and no qform to fall back on is an error: such an image cannot be placed
 * by origin, spacing and direction alone.
 *
 * Index order: vtkNIFTIImageReader reverses the slice order when the header's ijk axes are
 * left-handed (qfac = -1 in pixdim[0], or an sform with a negative determinant and no qform),
 * so the output's slice K holds the file's slice (dim[3] - 1 - K) there. The world position of
 * every voxel is the header's either way. A reflection that survives this (an sform with a
 * negative determinant beside a qform with qfac = +1) is kept as a direction matrix with
 * determinant -1. A negative pixdim becomes a positive spacing and a negated direction column.
 *
 * Output point data: the file's scalar array, with its type and name as vtkNIFTIImageReader
 * gives them ("NIFTI"; an unnamed array is named "Labels"), as the active scalars. Values are
 * not rescaled by scl_slope/scl_inter. Only the first volume of a 4-D file is read.
 *
 * Pieces: the reader produces the update extent it is asked for (clamped to the whole extent),
 * so each rank of a parallel pipeline reads and holds only its part of the image, with the
 * voxel values a whole read has at the same indices. A part of a .nii.gz is inflated as a
 * stream, keeping only the bytes of the asked slices; the stream is read up to the part's last
 * slice, so a rank reading the last slab inflates (without keeping) the slices before it, and
 * damage to the stream after a part's last slice goes unseen by that read.
 *
 * @warning A missing or unreadable file, or one that is not NIfTI, is reported with
 * vtkErrorMacro (one line naming the file) and the request fails; so is a header with a
 * datatype code NIfTI does not define, an axis of no voxels, or more voxels than its file could
 * hold even compressed (1032 bytes per byte, zlib's limit).
 *
 * @sa vtkNIFTIImageReader vtkCBC3DBCCLattice
 */
#ifndef vtkCBC3DNIfTIReader_h
#define vtkCBC3DNIfTIReader_h

#include "vtkCBC3DFiltersModule.h" // For export macro
#include "vtkImageAlgorithm.h"

#include <string> // For FrameSource
#include <vector> // For BoundaryPerSlice

class vtkInformationDoubleVectorKey;
class vtkNIFTIImageReader;

class VTKCBC3DFILTERS_EXPORT vtkCBC3DNIfTIReader : public vtkImageAlgorithm
{
public:
  static vtkCBC3DNIfTIReader* New();
  vtkTypeMacro(vtkCBC3DNIfTIReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The file to read: .nii or .nii.gz (a .hdr/.img pair also works). Default: none.
   */
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  /**
   * Whether the file is a NIfTI (or Analyze 7.5) file that vtkNIFTIImageReader can read.
   */
  int CanReadFile(VTK_FILEPATH const char* filename);

  /**
   * The rule that placed the last image read: "sform", "qform" or "voxel size"; "" before a
   * successful RequestInformation.
   */
  const char* GetFrameSource() const { return this->FrameSource.c_str(); }

  /**
   * Whether the last image's voxels were inflated in one piece (the whole image of a
   * single-file NIfTI-1 .nii.gz of one volume whose slices VTK keeps in the file's order: qfac
   * +1, and no sform of negative determinant without a qform; libdeflate, an order of magnitude
   * faster than zlib's streaming there) rather than read by vtkNIFTIImageReader. The voxels are
   * the same.
   */
  vtkGetMacro(InflatedAtOnce, bool);

  /**
   * Whether the last read, of a part of a file that InflatedAtOnce would take whole, streamed
   * the file through zlib and kept only the part's voxels, rather than leaving the part to
   * vtkNIFTIImageReader. The voxels are the same.
   */
  vtkGetMacro(InflatedSubExtent, bool);

  /**
   * Information key on the output: the boundary voxels (those whose value differs from that of
   * the voxel before them along x, y or z) of each slice of the whole image, along x, then y,
   * then z (nx + ny + nz values). vtkCBC3DMesher cuts its slabs over MPI ranks so that they
   * hold about as much of it each. RequestInformation sets
   * it when several MPI ranks run the pipeline, or when CountBoundaryPerSlice is on, for a NIfTI-1
   * file (.nii or .nii.gz) of one volume in VTK's slice order: one pass over the voxels, a slice
   * at a time, on each rank. The count is kept while the file stays the same.
   */
  static vtkInformationDoubleVectorKey* BOUNDARY_PER_SLICE();

  ///@{
  /**
   * Whether to give BOUNDARY_PER_SLICE on one process too. Default: off.
   */
  vtkSetMacro(CountBoundaryPerSlice, bool);
  vtkGetMacro(CountBoundaryPerSlice, bool);
  vtkBooleanMacro(CountBoundaryPerSlice, bool);
  ///@}

protected:
  vtkCBC3DNIfTIReader();
  ~vtkCBC3DNIfTIReader() override;

  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  char* FileName = nullptr;
  std::string FrameSource;
  bool InflatedAtOnce = false;
  bool InflatedSubExtent = false;
  bool CountBoundaryPerSlice = false;
  double Origin[3] = { 0.0, 0.0, 0.0 };
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  double Direction[9] = { 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0 };
  vtkNIFTIImageReader* Reader;

private:
  vtkCBC3DNIfTIReader(const vtkCBC3DNIfTIReader&) = delete;
  void operator=(const vtkCBC3DNIfTIReader&) = delete;

  // Run the inner reader's pass: information (extent null) or the data of `extent`, turning
  // its errors into one line of ours that names the file; warnings are passed on. False on
  // failure.
  bool RunReader(const int* extent);
  // The voxels of `extent` (within the whole extent) into `output`: a single-file .nii.gz by
  // InflateNIfTIVoxels, anything else by vtkNIFTIImageReader.
  bool ReadVoxels(vtkImageData* output, const int extent[6]);
  // The same from vtkNIFTIImageReader.
  bool ReadVoxelsWithReader(vtkImageData* output, const int extent[6]);
  bool ComputeFrame();
  // False, with an error, when the header gives an axis no voxels, or claims more voxel bytes
  // than the file could hold even compressed: the inner reader would read into an empty image,
  // or try to allocate them.
  bool VoxelsFitInFile();
  // Sets or removes BOUNDARY_PER_SLICE on `outInfo` (see there).
  void GiveBoundaryPerSlice(vtkInformation* outInfo);

  std::string CountedFile; // the file BoundaryPerSlice counts, with its time and size then
  long CountedTime = -1;
  unsigned long CountedSize = 0;
  std::vector<double> BoundaryPerSlice;
};

#endif
