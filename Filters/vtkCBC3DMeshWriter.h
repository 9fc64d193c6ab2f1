/**
 * @class   vtkCBC3DMeshWriter
 * @brief   Writes a labelled tet mesh in a solver's format, tissues, boundaries and interfaces
 *          tagged.
 *
 * Input: a vtkUnstructuredGrid of VTK_TETRA cells with an integer `Label` cell array. The file
 * name's extension picks the format: `.msh` (Gmsh 4.1, or 2.2 with MshVersion22), `.inp`
 * (Abaqus), `.mesh` (Medit), `.feb` (FEBio 4.0), `.xdmf` (dolfinx's XDMF, its heavy data in an
 * HDF5 `.h5` beside it, mesh.xdmf + mesh.h5), `.exo` (Exodus II: element blocks and side sets).
 * Tissues are named tissue_<label>, boundaries boundary_<label>, interfaces interface_<a>_<b>;
 * the formats without names carry the surface ids (Documentation/Exporting.md). The file (for
 * .xdmf both files) appears whole or not at all. In ParaView: File > Save Data with the CBC3D plugin loaded, or pvpython's
 * SaveData("mesh.msh", proxy=...).
 *
 * @sa vtkCBC3DTissueSurfaces
 */
#ifndef vtkCBC3DMeshWriter_h
#define vtkCBC3DMeshWriter_h

#include "vtkCBC3DFiltersModule.h" // For export macro
#include "vtkWriter.h"

class VTKCBC3DFILTERS_EXPORT vtkCBC3DMeshWriter : public vtkWriter
{
public:
  static vtkCBC3DMeshWriter* New();
  vtkTypeMacro(vtkCBC3DMeshWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to write; its extension picks the format.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Gmsh .msh: write version 2.2 instead of 4.1 (default off).
  vtkSetMacro(MshVersion22, vtkTypeBool);
  vtkGetMacro(MshVersion22, vtkTypeBool);
  vtkBooleanMacro(MshVersion22, vtkTypeBool);
  ///@}

  ///@{
  /// The label that stands for the outside on boundary triangles (default 0).
  vtkSetMacro(OutsideLabel, vtkTypeInt64);
  vtkGetMacro(OutsideLabel, vtkTypeInt64);
  ///@}

  /// Under MPI, asks upstream for this rank's piece (WriteData gathers the pieces).
  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

protected:
  vtkCBC3DMeshWriter() = default;
  ~vtkCBC3DMeshWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  char* FileName = nullptr;
  vtkTypeBool MshVersion22 = false;
  vtkTypeInt64 OutsideLabel = 0;

private:
  vtkCBC3DMeshWriter(const vtkCBC3DMeshWriter&) = delete;
  void operator=(const vtkCBC3DMeshWriter&) = delete;
};

#endif
