#include "vtkCBC3DBCCLattice.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DConvert.h"

#include "cbc3d/lattice/BCCLattice.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkUnstructuredGrid.h>

vtkStandardNewMacro(vtkCBC3DBCCLattice);

int vtkCBC3DBCCLattice::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  const std::shared_ptr<const cbc3d::LabelImage> image = this->ReadLabelImage(inputVector);
  if (!image)
  {
    return 0;
  }

  cbc3d::LatticeParams params;
  params.EdgeLength = this->EdgeLength;
  params.NumberOfThreads = this->NumberOfThreads;
  params.MaximumTets = this->MaximumNumberOfTets;
  cbc3d::TetMesh mesh;
  const cbc3d::Status status =
    cbc3d::BuildBCCLattice(*image, params, mesh, vtkCBC3DConvert::MakeProgress(this));
  if (!status.IsOk())
  {
    return this->EndOnFailure(status, output);
  }
  vtkCBC3DConvert::ToUnstructuredGrid(mesh, image->Codes, output);
  vtkNew<vtkDoubleArray> edge;
  edge->SetName(vtkCBC3DArrayNames::LatticeEdgeLength);
  edge->InsertNextValue(cbc3d::LatticeEdgeLengthFor(*image, params));
  output->GetFieldData()->AddArray(edge);
  return 1;
}

void vtkCBC3DBCCLattice::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EdgeLength: " << this->EdgeLength << " mm" << (this->EdgeLength == 0 ? " (auto)" : "")
     << "\n";
}
