#include "vtkCBC3DMeshQuality.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DConvert.h"

#include "cbc3d/Quality.h"

#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkUnstructuredGrid.h>

#include <vector>

vtkStandardNewMacro(vtkCBC3DMeshQuality);

namespace
{
template <typename ArrayT, typename ValueT>
void AddFieldArray(vtkFieldData* fields, const char* name, const std::vector<ValueT>& values)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    array->SetValue(static_cast<vtkIdType>(i), values[i]);
  }
  fields->AddArray(array);
}

void AddCellArray(vtkUnstructuredGrid* grid, const char* name, const std::vector<double>& values)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  grid->GetCellData()->AddArray(array);
}
} // namespace

int vtkCBC3DMeshQuality::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* input = vtkUnstructuredGrid::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);

  cbc3d::TetMesh mesh;
  std::string error;
  if (!vtkCBC3DConvert::FromUnstructuredGrid(input, mesh, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  this->UpdateProgress(0.1);
  cbc3d::TetDihedralExtremes perTet;
  const cbc3d::QualitySummary summary =
    cbc3d::SummarizeQuality(mesh, this->NumberOfThreads, &perTet);
  this->UpdateProgress(0.9);

  output->ShallowCopy(input);
  AddCellArray(output, vtkCBC3DArrayNames::MinDihedralAngle, perTet.MinDegrees);
  AddCellArray(output, vtkCBC3DArrayNames::MaxDihedralAngle, perTet.MaxDegrees);

  vtkNew<vtkFieldData> fields;
  fields->DeepCopy(input->GetFieldData());
  const cbc3d::DihedralSummary& all = summary.Overall;
  AddFieldArray<vtkIdTypeArray>(fields, vtkCBC3DArrayNames::TetCount, std::vector<vtkIdType>{ all.Tets });
  AddFieldArray<vtkDoubleArray>(fields, vtkCBC3DArrayNames::MinDihedralAngle, std::vector<double>{ all.MinDegrees });
  AddFieldArray<vtkDoubleArray>(fields, vtkCBC3DArrayNames::MaxDihedralAngle, std::vector<double>{ all.MaxDegrees });
  AddFieldArray<vtkIdTypeArray>(fields, vtkCBC3DArrayNames::InvertedTetCount, std::vector<vtkIdType>{ all.Inverted });

  std::vector<int> labels;
  std::vector<vtkIdType> tets, inverted;
  std::vector<double> minima, maxima;
  for (const auto& [label, figures] : summary.Tissues)
  {
    labels.push_back(label);
    tets.push_back(figures.Tets);
    minima.push_back(figures.MinDegrees);
    maxima.push_back(figures.MaxDegrees);
    inverted.push_back(figures.Inverted);
  }
  AddFieldArray<vtkIntArray>(fields, vtkCBC3DArrayNames::TissueLabel, labels);
  AddFieldArray<vtkIdTypeArray>(fields, vtkCBC3DArrayNames::TissueTetCount, tets);
  AddFieldArray<vtkDoubleArray>(fields, vtkCBC3DArrayNames::TissueMinDihedralAngle, minima);
  AddFieldArray<vtkDoubleArray>(fields, vtkCBC3DArrayNames::TissueMaxDihedralAngle, maxima);
  AddFieldArray<vtkIdTypeArray>(fields, vtkCBC3DArrayNames::TissueInvertedTetCount, inverted);
  output->SetFieldData(fields);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCBC3DMeshQuality::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
