#include "vtkCBC3DBCCLattice.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DConvert.h"

#include "cbc3d/BCCLattice.h"

#include <vtkDataObject.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkDataSetAttributes.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>

vtkStandardNewMacro(vtkCBC3DBCCLattice);

vtkCBC3DBCCLattice::vtkCBC3DBCCLattice()
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

void vtkCBC3DBCCLattice::AddBackgroundLabel(int label)
{
  if (std::find(this->BackgroundLabels.begin(), this->BackgroundLabels.end(), label) ==
    this->BackgroundLabels.end())
  {
    this->BackgroundLabels.push_back(label);
    this->Modified();
  }
}

void vtkCBC3DBCCLattice::RemoveAllBackgroundLabels()
{
  if (!this->BackgroundLabels.empty())
  {
    this->BackgroundLabels.clear();
    this->Modified();
  }
}

void vtkCBC3DBCCLattice::SetBackgroundLabel(int label)
{
  this->RemoveAllBackgroundLabels();
  this->AddBackgroundLabel(label);
}

int vtkCBC3DBCCLattice::GetNumberOfBackgroundLabels() const
{
  return static_cast<int>(this->BackgroundLabels.size());
}

int vtkCBC3DBCCLattice::GetBackgroundLabel(int index) const
{
  return this->BackgroundLabels.at(index);
}

int vtkCBC3DBCCLattice::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkCBC3DBCCLattice::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);

  cbc3d::LabelImage image;
  std::string error;
  vtkDataArray* labels = vtkCBC3DConvert::ChooseLabelArray(
    this->GetInputArrayToProcess(0, inputVector), this->GetInputArrayInformation(0), input);
  if (!vtkCBC3DConvert::ToLabelImage(input, labels, this->BackgroundLabels, image, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }

  cbc3d::LatticeParams params;
  params.EdgeLength = this->EdgeLength;
  params.NumberOfThreads = this->NumberOfThreads;
  cbc3d::TetMesh mesh;
  const cbc3d::Status status =
    cbc3d::BuildBCCLattice(image, params, mesh, vtkCBC3DConvert::MakeProgress(this));
  if (status.WasAborted())
  {
    output->Initialize();
    return 1; // an abort is the user's choice, not an error: the output is left empty
  }
  if (!status.IsOk())
  {
    vtkErrorMacro(<< status.GetMessage());
    return 0;
  }
  vtkCBC3DConvert::ToUnstructuredGrid(mesh, output);
  vtkNew<vtkDoubleArray> edge;
  edge->SetName(vtkCBC3DArrayNames::LatticeEdgeLength);
  edge->InsertNextValue(params.EdgeLength > 0 ? params.EdgeLength : cbc3d::DefaultLatticeEdgeLength(image));
  output->GetFieldData()->AddArray(edge);
  return 1;
}

void vtkCBC3DBCCLattice::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EdgeLength: " << this->EdgeLength << " mm" << (this->EdgeLength == 0 ? " (auto)" : "")
     << "\n";
  os << indent << "BackgroundLabels:";
  for (const int label : this->BackgroundLabels)
  {
    os << " " << label;
  }
  os << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
