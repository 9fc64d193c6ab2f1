#include "vtkCBC3DMesher.h"

#include "vtkCBC3DBCCLattice.h"
#include "vtkCBC3DDeformation.h"
#include "vtkCBC3DMeshQuality.h"
#include "vtkCBC3DRefinement.h"

#include "cbc3d/refinement/Refinement.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkUnstructuredGrid.h>

#include <string>
#include <vector>

vtkStandardNewMacro(vtkCBC3DMesher);

namespace
{
// Forwards a stage's progress into its slice of the mesher's, and the mesher's abort to it.
struct StageRelay
{
  vtkCBC3DMesher* Mesher;
  double Shift;
  double Scale;

  static void Forward(vtkObject* caller, unsigned long, void* clientData, void*)
  {
    auto* relay = static_cast<StageRelay*>(clientData);
    auto* stage = static_cast<vtkAlgorithm*>(caller);
    relay->Mesher->UpdateProgress(relay->Shift + relay->Scale * stage->GetProgress());
    if (relay->Mesher->CheckAbort())
    {
      stage->SetAbortExecute(1);
    }
  }
};

// Errors of a stage become the mesher's, so that callers observe one object.
class ErrorRelay : public vtkCommand
{
public:
  static ErrorRelay* New() { return new ErrorRelay; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    this->Message = data ? static_cast<const char*>(data) : "";
  }
  std::string Message;
};
} // namespace

int vtkCBC3DMesher::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  vtkNew<vtkImageData> image;
  image->ShallowCopy(vtkImageData::GetData(inputVector[0]));

  vtkNew<vtkCBC3DBCCLattice> lattice;
  vtkNew<vtkCBC3DRefinement> refinement;
  vtkNew<vtkCBC3DDeformation> deformation;
  vtkNew<vtkCBC3DMeshQuality> quality;
  lattice->SetEdgeLength(this->EdgeLength);
  refinement->SetFidelity(this->Fidelity);
  refinement->SetBoundaryDistance(this->BoundaryDistance);
  refinement->SetMinimumEdgeLength(this->MinimumEdgeLength);
  this->CopySizeControlsTo(lattice);
  this->CopySizeControlsTo(refinement);
  this->CopySizeControlsTo(deformation);
  const bool refine = refinement->AsksForRefinement();
  deformation->SetIterations(this->Iterations);
  deformation->SetPattern(this->Pattern);
  deformation->SetTargetPlacement(this->TargetPlacement);
  deformation->SetKeepVolumes(this->KeepVolumes);
  vtkInformation* arrayRequest = this->GetInputArrayInformation(0);
  const char* arrayName = arrayRequest && arrayRequest->Has(vtkDataObject::FIELD_NAME())
    ? arrayRequest->Get(vtkDataObject::FIELD_NAME())
    : nullptr;

  // The stages in order, with their share of the progress bar.
  struct Stage
  {
    vtkCBC3DAlgorithm* Filter;
    const char* Name;
    double Share;
  };
  std::vector<Stage> stages = { { lattice, "BCC lattice", 0.15 } };
  if (refine)
  {
    stages.push_back({ refinement, "Red-green refinement", 0.25 });
  }
  if (this->Iterations > 0)
  {
    stages.push_back({ deformation, "Deformation", 0.5 });
  }
  stages.push_back({ quality, "Quality", 0.1 });

  vtkAlgorithm* previous = nullptr;
  double shift = 0.0, total = 0.0;
  for (const Stage& stage : stages)
  {
    total += stage.Share;
  }
  for (const Stage& stage : stages)
  {
    vtkCBC3DAlgorithm* filter = stage.Filter;
    filter->RemoveAllBackgroundLabels();
    for (const vtkTypeInt64 label : this->BackgroundLabels)
    {
      filter->AddBackgroundLabel(label);
    }
    filter->SetNumberOfThreads(this->NumberOfThreads);
    if (arrayName && *arrayName)
    {
      filter->SetInputArrayToProcess(0, previous ? 1 : 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, arrayName);
    }
    if (previous)
    {
      filter->SetInputConnection(0, previous->GetOutputPort());
      filter->SetInputData(1, image);
    }
    else
    {
      filter->SetInputData(0, image);
    }
    StageRelay relay{ this, shift / total, stage.Share / total };
    vtkNew<vtkCallbackCommand> forward;
    forward->SetCallback(&StageRelay::Forward);
    forward->SetClientData(&relay);
    filter->AddObserver(vtkCommand::ProgressEvent, forward);
    vtkNew<ErrorRelay> errors;
    filter->AddObserver(vtkCommand::ErrorEvent, errors);
    this->SetProgressText(stage.Name);
    filter->Update();
    filter->RemoveObserver(forward);
    if (this->CheckAbort())
    {
      output->Initialize();
      return 1;
    }
    if (!errors->Message.empty())
    {
      // Keep the stage's own words: VTK formats "... Class (0x...): message".
      const std::size_t marker = errors->Message.find("): ");
      vtkErrorMacro(<< stage.Name << ": "
                    << (marker == std::string::npos ? errors->Message : errors->Message.substr(marker + 3)));
      return 0;
    }
    shift += stage.Share;
    previous = filter;
  }
  output->ShallowCopy(quality->GetOutput());
  this->SetProgressText(nullptr);
  return 1;
}

double vtkCBC3DMesher::GetAutomaticBoundaryDistance() const
{
  // Refinement takes 3/8 of the lattice's longest edges, its cube edges.
  const double lattice = this->EdgeLength > 0.0 ? this->EdgeLength : this->AutomaticLatticeEdge();
  return lattice > 0.0 ? cbc3d::DefaultBoundaryDistance(lattice) : 0.0;
}

void vtkCBC3DMesher::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EdgeLength: " << this->EdgeLength << " mm" << (this->EdgeLength == 0 ? " (auto)" : "") << "\n";
  os << indent << "Fidelity: " << this->Fidelity << "\n";
  os << indent << "MinimumEdgeLength: " << this->MinimumEdgeLength << " mm\n";
  os << indent << "BoundaryDistance: " << this->BoundaryDistance << " mm\n";
  os << indent << "Iterations: " << this->Iterations << "\n";
  os << indent << "Pattern: " << this->Pattern << "\n";
  os << indent << "TargetPlacement: " << this->TargetPlacement << "\n";
  os << indent << "KeepVolumes: " << (this->KeepVolumes ? "on" : "off") << "\n";
}
