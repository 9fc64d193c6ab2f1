/**
 * @class   vtkCBC3DBCCLattice
 * @brief   Fill the tissues of a label image with a body-centred cubic tetrahedral lattice.
 *
 * The first stage of the CBC3D method (Drakopoulos et al., IMR 2014, section 3.2). The input
 * is a 3-D label map: a vtkImageData whose label array (chosen with SetInputArrayToProcess;
 * default: the active point scalars) holds integers, in any integer type or as a float array
 * of whole numbers. Every label not listed as background is a tissue.
 *
 * The lattice covers the tissues' bounding box with cubes of edge EdgeLength (mm) aligned with
 * the image axes. Its vertices are the cube corners and centres; every pair of face-adjacent
 * cube centres carries four tets, each with four 60 degree and two 90 degree dihedral angles.
 * A tet holding no tissue voxel centre (nor, for a tet smaller than a voxel, any tissue sample
 * of a finer sub-grid) is dropped; every tissue voxel centre lies in some kept tet.
 *
 * The output lives in the image's physical frame: origin, spacing and direction matrix are
 * honoured, the image is never resampled, and every tet is positively oriented in VTK's
 * convention even when the direction matrix is a reflection.
 *
 * Output cell data: `Label` (vtkIntArray), each tet's majority tissue label, with the image's
 * label values unchanged. Field data: `LatticeEdgeLength` (vtkDoubleArray, mm), the cube edge
 * used.
 *
 * @warning Bad input (no label array, several components, fractional values, a 2-D image, no
 * tissue, a non-positive or memory-exhausting EdgeLength) is reported with vtkErrorMacro and
 * produces an empty output.
 *
 * @sa vtkCBC3DNIfTIReader
 */
#ifndef vtkCBC3DBCCLattice_h
#define vtkCBC3DBCCLattice_h

#include "vtkCBC3DFiltersModule.h" // For export macro
#include "vtkCBC3DAlgorithm.h"

class VTKCBC3DFILTERS_EXPORT vtkCBC3DBCCLattice : public vtkCBC3DAlgorithm
{
public:
  static vtkCBC3DBCCLattice* New();
  vtkTypeMacro(vtkCBC3DBCCLattice, vtkCBC3DAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Edge of the lattice cube in millimetres (the paper's BCC_size). 0 (the default) picks
   * 8 times the finest voxel spacing, the paper's choice.
   */
  vtkSetMacro(EdgeLength, double);
  vtkGetMacro(EdgeLength, double);
  ///@}

  /**
   * The edge length that EdgeLength 0 stands for, from the image's spacing as of the last
   * UpdateInformation (0 while unknown): the value the ParaView panel fills in.
   */
  double GetAutomaticEdgeLength() const { return this->AutomaticLatticeEdge(); }

protected:
  vtkCBC3DBCCLattice() = default;
  ~vtkCBC3DBCCLattice() override = default;

  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double EdgeLength = 0.0;

private:
  vtkCBC3DBCCLattice(const vtkCBC3DBCCLattice&) = delete;
  void operator=(const vtkCBC3DBCCLattice&) = delete;
};

#endif
