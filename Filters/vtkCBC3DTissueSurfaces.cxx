#include "vtkCBC3DTissueSurfaces.h"

#include "vtkCBC3DConvert.h"

#include <vtkInformation.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

vtkStandardNewMacro(vtkCBC3DTissueSurfaces);

void vtkCBC3DTissueSurfaces::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OutsideLabel: " << this->OutsideLabel << "\n";
}

int vtkCBC3DTissueSurfaces::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  return 1;
}

int vtkCBC3DTissueSurfaces::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  cbc3d::TaggedMesh tagged;
  std::string error;
  if (!vtkCBC3DConvert::ToTaggedMesh(vtkUnstructuredGrid::GetData(inputVector[0]), this->OutsideLabel, tagged, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  vtkCBC3DConvert::ToPolyData(tagged, vtkPolyData::GetData(outputVector));
  return 1;
}
