#include "vtkCBC3DRefinement.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DBCCLattice.h"
#include "vtkCBC3DConvert.h"
#include "vtkCBC3DLabelValues.h"

#include "cbc3d/refinement/Refinement.h"

#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

vtkStandardNewMacro(vtkCBC3DRefinement);

vtkCBC3DRefinement::vtkCBC3DRefinement()
  : vtkCBC3DAlgorithm(ImageInput::Port1)
{
}

namespace
{
// The CBC3D BCC lattice that makes the mesh on port 0, if one does. ParaView follows every
// filter's output with a vtkPVPostFilter (array conversions on demand), looked through here.
vtkCBC3DBCCLattice* InputLattice(vtkAlgorithm* producer)
{
  if (producer && producer->IsA("vtkPVPostFilter") && producer->GetNumberOfInputConnections(0) == 1)
  {
    producer = producer->GetInputAlgorithm(0, 0);
  }
  return vtkCBC3DBCCLattice::SafeDownCast(producer);
}
} // namespace

int vtkCBC3DRefinement::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->Superclass::RequestInformation(request, inputVector, outputVector);
  // The lattice's own RequestInformation, upstream, has just read the image's spacing.
  vtkCBC3DBCCLattice* lattice = this->GetNumberOfInputConnections(0) == 1
    ? InputLattice(this->GetInputAlgorithm(0, 0))
    : nullptr;
  this->InputLatticeEdge = 0.0;
  if (lattice)
  {
    const double edge = lattice->GetEdgeLength();
    this->InputLatticeEdge = edge > 0.0 ? edge : lattice->GetAutomaticEdgeLength();
  }
  return 1;
}

double vtkCBC3DRefinement::GetAutomaticBoundaryDistance() const
{
  // A BCC lattice's longest edges are its cube edges.
  const double edge = this->InputLatticeEdge;
  return edge > 0.0 ? cbc3d::DefaultBoundaryDistance(edge) : 0.0;
}

int vtkCBC3DRefinement::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* input = vtkUnstructuredGrid::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  cbc3d::TetMesh lattice;
  std::shared_ptr<const cbc3d::LabelImage> image;
  if (!this->ReadMeshAndImage(inputVector, lattice, image))
  {
    return 0;
  }
  cbc3d::RefinementParams params;
  params.Fidelity = this->Fidelity;
  params.MinimumEdgeLength = this->MinimumEdgeLength;
  params.MinimumComponentVoxels = this->MinimumComponentVoxels;
  params.BoundaryDistance = this->BoundaryDistance;
  params.SoundLabels = this->SoundLabels;
  params.NumberOfThreads = this->NumberOfThreads;
  params.MaximumTets = this->MaximumNumberOfTets;
  params.Ranks = this->Ranks;
  if (!this->ReadTissueCodes(this->TissueFidelity, *image, params.FidelityByTissue) ||
    !this->ReadEdgeLimits(*image, params.MaximumEdge))
  {
    return 0;
  }
  cbc3d::TetMesh mesh;
  cbc3d::RefinementResult result;
  const cbc3d::Status status =
    cbc3d::RefineMesh(*image, lattice, params, mesh, result, vtkCBC3DConvert::MakeProgress(this));
  if (!status.IsOk())
  {
    return this->EndOnFailure(status, output);
  }
  vtkCBC3DConvert::ToUnstructuredGrid(mesh, image->Codes, output);

  namespace names = vtkCBC3DArrayNames;
  vtkNew<vtkUnsignedCharArray> levels;
  levels->SetName(names::RefinementLevel);
  levels->SetNumberOfValues(static_cast<vtkIdType>(result.Levels.size()));
  std::copy(result.Levels.begin(), result.Levels.end(), levels->GetPointer(0));
  output->GetCellData()->AddArray(levels);

  vtkFieldData* fields = output->GetFieldData();
  fields->DeepCopy(input->GetFieldData());
  vtkNew<vtkIntArray> passes;
  passes->SetName(names::RefinementPasses);
  passes->InsertNextValue(result.Passes);
  fields->AddArray(passes);
  vtkNew<vtkStringArray> reason;
  reason->SetName(names::RefinementStopReason);
  reason->InsertNextValue(result.StopReason);
  fields->AddArray(reason);
  vtkNew<vtkDoubleArray> boundaryDistance, boundaryGap;
  boundaryDistance->SetName(names::RefinementBoundaryDistance);
  boundaryDistance->InsertNextValue(result.BoundaryDistance);
  fields->AddArray(boundaryDistance);
  boundaryGap->SetName(names::RefinementBoundaryGap);
  boundaryGap->InsertNextValue(result.LargestBoundaryGap);
  fields->AddArray(boundaryGap);
  vtkNew<vtkIdTypeArray> relabelled;
  relabelled->SetName(names::RefinementRelabelledTets);
  relabelled->InsertNextValue(result.Relabelled);
  fields->AddArray(relabelled);
  vtkNew<vtkIdTypeArray> overlong;
  overlong->SetName(names::RefinementOverlongTets);
  overlong->InsertNextValue(static_cast<vtkIdType>(result.OverlongTets));
  fields->AddArray(overlong);
  std::vector<std::int32_t> labels;
  vtkNew<vtkDoubleArray> f1, f2;
  f1->SetName(names::FidelityF1);
  f2->SetName(names::FidelityF2);
  vtkNew<vtkIdTypeArray> components, kept;
  components->SetName(names::FidelityComponents);
  kept->SetName(names::FidelityComponentsInMesh);
  for (const cbc3d::TissueFidelity& tissue : result.Tissues)
  {
    labels.push_back(tissue.Label);
    f1->InsertNextValue(tissue.F1);
    f2->InsertNextValue(tissue.F2);
    components->InsertNextValue(tissue.Components);
    kept->InsertNextValue(tissue.ComponentsInMesh);
  }
  fields->AddArray(vtkCBC3DLabelValues::FromCodes(labels, image->Codes, names::FidelityLabel));
  for (vtkAbstractArray* array : { static_cast<vtkAbstractArray*>(f1), static_cast<vtkAbstractArray*>(f2),
         static_cast<vtkAbstractArray*>(components), static_cast<vtkAbstractArray*>(kept) })
  {
    fields->AddArray(array);
  }
  return 1;
}

void vtkCBC3DRefinement::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Fidelity: " << this->Fidelity << "\n";
  os << indent << "MinimumEdgeLength: " << this->MinimumEdgeLength << " mm"
     << (this->MinimumEdgeLength == 0 ? " (the voxel size)" : "") << "\n";
  os << indent << "MinimumComponentVoxels: " << this->MinimumComponentVoxels << "\n";
  os << indent << "BoundaryDistance: " << this->BoundaryDistance << " mm"
     << (this->BoundaryDistance == 0 ? " (3/8 of the longest edge)" : this->BoundaryDistance < 0 ? " (none)" : "")
     << "\n";
  os << indent << "SoundLabels: " << (this->SoundLabels ? "on" : "off") << "\n";
}
