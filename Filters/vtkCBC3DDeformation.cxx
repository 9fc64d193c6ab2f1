#include "vtkCBC3DDeformation.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DConvert.h"

#include "cbc3d/deformation/Deformation.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

vtkStandardNewMacro(vtkCBC3DDeformation);

namespace
{
// The fixed points and volume offsets of a piece of a larger mesh, where the input has them.
void ReadPieceArrays(vtkUnstructuredGrid* input, const cbc3d::LabelImage& image, cbc3d::DeformationParams& params)
{
  if (vtkDataArray* fixed = input->GetPointData()->GetArray(vtkCBC3DArrayNames::FixedPoints))
  {
    params.FixedPoints.resize(static_cast<std::size_t>(fixed->GetNumberOfTuples()));
    for (vtkIdType p = 0; p < fixed->GetNumberOfTuples(); ++p)
    {
      params.FixedPoints[p] = fixed->GetComponent(p, 0) != 0.0;
    }
  }
  vtkDataArray* window = input->GetFieldData()->GetArray(vtkCBC3DArrayNames::VoxelWindow);
  if (window && window->GetNumberOfComponents() == 5 && window->GetNumberOfTuples() == 1)
  {
    params.VoxelWindow.Set = true;
    params.VoxelWindow.Normal = Eigen::Vector3d(window->GetComponent(0, 0), window->GetComponent(0, 1), window->GetComponent(0, 2));
    params.VoxelWindow.Lower = window->GetComponent(0, 3);
    params.VoxelWindow.Upper = window->GetComponent(0, 4);
  }
  vtkDataArray* offsets = input->GetFieldData()->GetArray(vtkCBC3DArrayNames::VolumeOffsets);
  for (vtkIdType t = 0; offsets && offsets->GetNumberOfComponents() == 2 && t < offsets->GetNumberOfTuples(); ++t)
  {
    std::int32_t code = 0;
    if (image.Codes.FindCode(static_cast<vtkTypeInt64>(offsets->GetComponent(t, 0)), code))
    {
      params.VolumeOffsets[code] += offsets->GetComponent(t, 1);
    }
  }
}
} // namespace

vtkCBC3DDeformation::vtkCBC3DDeformation()
  : vtkCBC3DAlgorithm(ImageInput::Port1)
{
}

const char* vtkCBC3DDeformation::GetPatternAsString() const
{
  static const char* names[] = { "Vertex", "Edge", "Face", "None" };
  return names[this->Pattern];
}

const char* vtkCBC3DDeformation::GetTargetPlacementAsString() const
{
  return this->TargetPlacement == VOXEL_FACE ? "VoxelFace" : "VoxelCentre";
}

void vtkCBC3DDeformation::SetTissueYoungModulus(vtkTypeInt64 label, double modulus)
{
  this->YoungModuli[label] = modulus;
  this->Modified();
}

void vtkCBC3DDeformation::RemoveAllTissueYoungModuli()
{
  if (!this->YoungModuli.empty())
  {
    this->YoungModuli.clear();
    this->Modified();
  }
}

int vtkCBC3DDeformation::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* input = vtkUnstructuredGrid::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  cbc3d::TetMesh mesh;
  std::shared_ptr<const cbc3d::LabelImage> image;
  if (!this->ReadMeshAndImage(inputVector, mesh, image))
  {
    return 0;
  }
  for (const auto& entry : this->YoungModuli)
  {
    if (!(entry.second > 0.0))
    {
      vtkErrorMacro(<< "the Young's modulus of tissue " << entry.first << " must be positive");
      return 0;
    }
  }
  if (!(this->PoissonRatio > -1.0 && this->PoissonRatio < 0.5))
  {
    vtkErrorMacro(<< "Poisson's ratio must lie between -1 and 0.5, not " << this->PoissonRatio);
    return 0;
  }
  cbc3d::DeformationParams params;
  params.Iterations = this->Iterations;
  params.Pattern = static_cast<cbc3d::TargetPattern>(this->Pattern);
  params.Placement = this->TargetPlacement == VOXEL_FACE ? cbc3d::TargetPlacement::VoxelFace
                                                         : cbc3d::TargetPlacement::VoxelCentre;
  params.Penalty = this->Penalty;
  params.MinimumDihedralAngle = this->MinimumDihedralAngle;
  params.RigidAlignment = this->RigidAlignment;
  params.KeepVolumes = this->KeepVolumes;
  params.DefaultMaterial.PoissonRatio = this->PoissonRatio;
  for (const auto& entry : this->YoungModuli)
  {
    std::int32_t code = 0;
    if (image->Codes.FindCode(entry.first, code)) // a tissue the image lacks needs no material
    {
      params.Materials[code] = cbc3d::Material{ entry.second, this->PoissonRatio };
    }
  }
  params.NumberOfThreads = this->NumberOfThreads;
  ReadPieceArrays(input, *image, params);
  if (!this->ReadEdgeLimits(*image, params.MaximumEdge))
  {
    return 0;
  }
  std::vector<Eigen::Vector3d> moved;
  cbc3d::DeformationResult result;
  const cbc3d::Status status =
    cbc3d::DeformPoints(*image, mesh, params, moved, result, vtkCBC3DConvert::MakeProgress(this));
  if (!status.IsOk())
  {
    return this->EndOnFailure(status, output);
  }
  // Same cells and arrays as the input, moved points.
  output->ShallowCopy(input);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(moved.size()));
  vtkNew<vtkDoubleArray> displacement;
  displacement->SetName(vtkCBC3DArrayNames::Displacement);
  displacement->SetNumberOfComponents(3);
  displacement->SetNumberOfTuples(static_cast<vtkIdType>(moved.size()));
  for (std::size_t p = 0; p < moved.size(); ++p)
  {
    points->SetPoint(static_cast<vtkIdType>(p), moved[p].data());
    displacement->SetTuple(static_cast<vtkIdType>(p), result.Displacement[p].data());
  }
  output->SetPoints(points);
  vtkNew<vtkPointData> pointData;
  pointData->ShallowCopy(input->GetPointData());
  output->GetPointData()->ShallowCopy(pointData);
  output->GetPointData()->AddArray(displacement);

  vtkNew<vtkFieldData> fields;
  fields->DeepCopy(input->GetFieldData());
  vtkNew<vtkIntArray> iterations;
  iterations->SetName(vtkCBC3DArrayNames::DeformationIterations);
  iterations->InsertNextValue(result.Iterations);
  vtkNew<vtkStringArray> reason;
  reason->SetName(vtkCBC3DArrayNames::DeformationStopReason);
  reason->InsertNextValue(result.StopReason);
  vtkNew<vtkIdTypeArray> sources, targets;
  sources->SetName(vtkCBC3DArrayNames::DeformationSources);
  sources->InsertNextValue(static_cast<vtkIdType>(result.Sources));
  targets->SetName(vtkCBC3DArrayNames::DeformationTargets);
  targets->InsertNextValue(static_cast<vtkIdType>(result.Targets));
  fields->AddArray(iterations);
  fields->AddArray(reason);
  fields->AddArray(sources);
  fields->AddArray(targets);
  output->SetFieldData(fields);
  return 1;
}

void vtkCBC3DDeformation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Iterations: " << this->Iterations << "\n";
  os << indent << "Pattern: " << this->GetPatternAsString() << "\n";
  os << indent << "TargetPlacement: " << this->GetTargetPlacementAsString() << "\n";
  os << indent << "Penalty: " << this->Penalty << "\n";
  os << indent << "MinimumDihedralAngle: " << this->MinimumDihedralAngle << " degrees\n";
  os << indent << "RigidAlignment: " << (this->RigidAlignment ? "on" : "off") << "\n";
  os << indent << "KeepVolumes: " << (this->KeepVolumes ? "on" : "off") << "\n";
  os << indent << "PoissonRatio: " << this->PoissonRatio << "\n";
  for (const auto& entry : this->YoungModuli)
  {
    os << indent << "YoungModulus of tissue " << entry.first << ": " << entry.second << "\n";
  }
}
