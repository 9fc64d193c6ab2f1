#include "vtkCBC3DAlgorithm.h"

#include "vtkCBC3DConvert.h"
#include "vtkCBC3DLabelImageCache.h"

#include "cbc3d/base/EdgeLengthLimits.h"
#include "cbc3d/base/LabelCodes.h"
#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/Status.h"
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/lattice/BCCLattice.h"
#include "cbc3d/refinement/Refinement.h"

#include <vtkDataObject.h>
#include <vtkDataSetAttributes.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>

vtkCBC3DAlgorithm::vtkCBC3DAlgorithm(ImageInput input)
  : ImagePort(input == ImageInput::Port0 ? 0 : 1)
  , ImageOptional(input == ImageInput::OptionalPort1)
{
  this->SetNumberOfInputPorts(this->ImagePort + 1);
  this->SetInputArrayToProcess(0, this->ImagePort, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
    vtkDataSetAttributes::SCALARS);
}

void vtkCBC3DAlgorithm::SetImageConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(this->ImagePort, output);
}

void vtkCBC3DAlgorithm::SetImageData(vtkImageData* image)
{
  this->SetInputData(this->ImagePort, image);
}

int vtkCBC3DAlgorithm::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == this->ImagePort)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    if (this->ImageOptional)
    {
      info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    }
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  return 1;
}

bool vtkCBC3DAlgorithm::HasImage(vtkInformationVector** inputVector) const
{
  return inputVector[this->ImagePort]->GetNumberOfInformationObjects() > 0;
}

int vtkCBC3DAlgorithm::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  std::fill_n(this->InformationSpacing, 3, 0.0);
  vtkInformation* image = inputVector[this->ImagePort]->GetInformationObject(0);
  if (image && image->Has(vtkDataObject::SPACING()))
  {
    image->Get(vtkDataObject::SPACING(), this->InformationSpacing);
  }
  return 1;
}

namespace
{
// The spacing as the core takes it, or none where some axis has no positive, finite spacing.
bool KnownSpacing(const double spacing[3], Eigen::Vector3d& out)
{
  out = Eigen::Vector3d(spacing[0], spacing[1], spacing[2]);
  return out.allFinite() && (out.array() > 0.0).all();
}
} // namespace

double vtkCBC3DAlgorithm::AutomaticLatticeEdge() const
{
  Eigen::Vector3d spacing;
  return KnownSpacing(this->InformationSpacing, spacing) ? cbc3d::DefaultLatticeEdgeLength(spacing)
                                                         : 0.0;
}

double vtkCBC3DAlgorithm::AutomaticMinimumEdge() const
{
  Eigen::Vector3d spacing;
  return KnownSpacing(this->InformationSpacing, spacing) ? cbc3d::DefaultMinimumEdgeLength(spacing)
                                                         : 0.0;
}

void vtkCBC3DAlgorithm::AddBackgroundLabel(vtkTypeInt64 label)
{
  if (std::find(this->BackgroundLabels.begin(), this->BackgroundLabels.end(), label) ==
    this->BackgroundLabels.end())
  {
    this->BackgroundLabels.push_back(label);
    this->Modified();
  }
}

void vtkCBC3DAlgorithm::RemoveAllBackgroundLabels()
{
  if (!this->BackgroundLabels.empty())
  {
    this->BackgroundLabels.clear();
    this->Modified();
  }
}

void vtkCBC3DAlgorithm::SetBackgroundLabel(vtkTypeInt64 label)
{
  this->RemoveAllBackgroundLabels();
  this->AddBackgroundLabel(label);
}

int vtkCBC3DAlgorithm::GetNumberOfBackgroundLabels() const
{
  return static_cast<int>(this->BackgroundLabels.size());
}

vtkTypeInt64 vtkCBC3DAlgorithm::GetBackgroundLabel(int index) const
{
  return this->BackgroundLabels.at(index);
}

std::shared_ptr<const cbc3d::LabelImage> vtkCBC3DAlgorithm::ReadLabelImage(
  vtkInformationVector** inputVector, const std::vector<std::int64_t>& otherValues)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[this->ImagePort]);
  vtkDataArray* labels =
    vtkCBC3DConvert::ChooseLabelArray(this->GetInputArrayInformation(0), input);
  std::string error;
  auto image = vtkCBC3DLabelImageCache::Get(
    input, labels, this->BackgroundLabels, otherValues, error, this->NumberOfThreads);
  if (!image)
  {
    vtkErrorMacro(<< error);
  }
  return image;
}

bool vtkCBC3DAlgorithm::ReadMesh(
  vtkInformationVector** inputVector, cbc3d::TetMesh& mesh, cbc3d::LabelCodes& codes)
{
  vtkUnstructuredGrid* grid = vtkUnstructuredGrid::GetData(inputVector[0]);
  std::vector<std::int64_t> values(this->BackgroundLabels.begin(), this->BackgroundLabels.end());
  std::string error;
  const bool read = vtkCBC3DConvert::MeshLabelValues(grid, values, error) &&
    vtkCBC3DConvert::FromUnstructuredGrid(
      grid, mesh, error, codes = cbc3d::LabelCodes::ForValues(std::move(values)));
  if (!read)
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}

bool vtkCBC3DAlgorithm::ReadMeshAndImage(vtkInformationVector** inputVector, cbc3d::TetMesh& mesh,
  std::shared_ptr<const cbc3d::LabelImage>& image)
{
  vtkUnstructuredGrid* grid = vtkUnstructuredGrid::GetData(inputVector[0]);
  std::vector<std::int64_t> meshValues;
  std::string error;
  if (!vtkCBC3DConvert::MeshLabelValues(grid, meshValues, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  image = this->ReadLabelImage(inputVector, meshValues);
  if (!image)
  {
    return false;
  }
  if (!vtkCBC3DConvert::FromUnstructuredGrid(grid, mesh, error, image->Codes))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}

int vtkCBC3DAlgorithm::EndOnFailure(const cbc3d::Status& status, vtkUnstructuredGrid* output)
{
  output->Initialize();
  if (status.WasAborted())
  {
    return 1;
  }
  vtkErrorMacro(<< status.GetMessage());
  return 0;
}

void vtkCBC3DAlgorithm::SetTissueValue(std::map<long long, double>& values, double label, double value)
{
  values[static_cast<long long>(label)] = value;
  this->Modified();
}

void vtkCBC3DAlgorithm::ClearTissueValues(std::map<long long, double>& values)
{
  if (!values.empty())
  {
    values.clear();
    this->Modified();
  }
}

void vtkCBC3DAlgorithm::SetTissueMaximumEdgeLength(double label, double length)
{
  this->SetTissueValue(this->TissueMaximumEdgeLength, label, length);
}

void vtkCBC3DAlgorithm::RemoveAllTissueMaximumEdgeLengths()
{
  this->ClearTissueValues(this->TissueMaximumEdgeLength);
}

void vtkCBC3DAlgorithm::SetTissueFidelity(double label, double fidelity)
{
  this->SetTissueValue(this->TissueFidelity, label, fidelity);
}

void vtkCBC3DAlgorithm::RemoveAllTissueFidelities()
{
  this->ClearTissueValues(this->TissueFidelity);
}

bool vtkCBC3DAlgorithm::ReadTissueCodes(const std::map<long long, double>& byValue,
  const cbc3d::LabelImage& image, std::map<std::int32_t, double>& byCode)
{
  std::string error;
  if (!vtkCBC3DConvert::ToTissueCodes(byValue, image, byCode, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}

bool vtkCBC3DAlgorithm::ReadEdgeLimits(const cbc3d::LabelImage& image, cbc3d::EdgeLengthLimits& limits)
{
  limits.All = this->MaximumEdgeLength;
  return this->ReadTissueCodes(this->TissueMaximumEdgeLength, image, limits.ByTissue);
}

void vtkCBC3DAlgorithm::CopySizeControlsTo(vtkCBC3DAlgorithm* stage) const
{
  stage->SetMaximumNumberOfTets(this->MaximumNumberOfTets);
  stage->SetMaximumEdgeLength(this->MaximumEdgeLength);
  stage->RemoveAllTissueMaximumEdgeLengths();
  for (const auto& [label, length] : this->TissueMaximumEdgeLength)
    stage->SetTissueMaximumEdgeLength(static_cast<double>(label), length);
  stage->RemoveAllTissueFidelities();
  for (const auto& [label, fidelity] : this->TissueFidelity)
    stage->SetTissueFidelity(static_cast<double>(label), fidelity);
}

bool vtkCBC3DAlgorithm::SizeControlsAskForRefinement() const
{
  return this->MaximumEdgeLength > 0.0 || !this->TissueMaximumEdgeLength.empty() ||
    std::any_of(this->TissueFidelity.begin(), this->TissueFidelity.end(),
      [](const auto& entry) { return entry.second > 0.0; });
}

void vtkCBC3DAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BackgroundLabels:";
  for (const vtkTypeInt64 label : this->BackgroundLabels)
  {
    os << " " << label;
  }
  os << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "MaximumEdgeLength: " << this->MaximumEdgeLength << " mm";
  for (const auto& [label, length] : this->TissueMaximumEdgeLength)
    os << ", tissue " << label << ": " << length << " mm";
  os << "\n";
  os << indent << "TissueFidelity:";
  for (const auto& [label, fidelity] : this->TissueFidelity)
    os << " " << label << ": " << fidelity;
  os << "\n";
  os << indent << "MaximumNumberOfTets: " << this->MaximumNumberOfTets << "\n";
}
