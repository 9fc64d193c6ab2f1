#include "vtkCBC3DMesher.h"

#include "vtkCBC3DBCCLattice.h"
#include "vtkCBC3DDeformation.h"
#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DConvert.h"
#include "vtkCBC3DMeshQuality.h"
#include "vtkCBC3DPieces.h"
#include "vtkCBC3DRankDeformation.h"
#include "vtkCBC3DRefinement.h"
#include "vtkCBC3DSeams.h"

#include "cbc3d/refinement/RankPasses.h"
#include "cbc3d/refinement/Refinement.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPointSet.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <numeric>

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

// A stage of the mesher and its share of the progress bar.
struct Stage
{
  vtkCBC3DAlgorithm* Filter;
  const char* Name;
  double Share;
};

// The stages a run goes through, with their shares of the progress bar.
std::vector<Stage> ChooseStages(vtkCBC3DAlgorithm* lattice, vtkCBC3DRefinement* refinement,
  vtkCBC3DAlgorithm* deformation, vtkCBC3DAlgorithm* quality, bool deforms)
{
  std::vector<Stage> stages = { { lattice, "BCC lattice", 0.15 } };
  if (refinement->AsksForRefinement())
  {
    stages.push_back({ refinement, "Red-green refinement", 0.25 });
  }
  if (deforms)
  {
    stages.push_back({ deformation, "Deformation", 0.5 });
  }
  stages.push_back({ quality, "Quality", 0.1 });
  return stages;
}
} // namespace

struct vtkCBC3DMesher::Piece
{
  vtkMultiProcessController* Controller = nullptr;
  vtkCBC3DPieces::SlabPlan Plan;
  int WholeLower[3] = { 0, 0, 0 };
  int WholeUpper[3] = { -1, -1, -1 };
  bool HasTissue = false;
  std::vector<std::int64_t> CutKeys;
  double LatticeEdge = 0.0; // mm
  std::shared_ptr<const cbc3d::RankPasses> Passes;
};

namespace
{
// The MPI controller where the pipeline asks for one piece per rank; null for a serial run.
vtkMultiProcessController* RankController(vtkInformation* outInfo)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int pieces = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    : 1;
  return controller && pieces > 1 && controller->GetNumberOfProcesses() == pieces ? controller : nullptr;
}
} // namespace

int vtkCBC3DMesher::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestInformation(request, inputVector, outputVector))
  {
    return 0;
  }
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkCBC3DMesher::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  int whole[6], extent[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  std::copy(whole, whole + 6, extent);
  vtkMultiProcessController* controller = RankController(outInfo);
  const double h = this->EdgeLength > 0.0 ? this->EdgeLength : this->AutomaticLatticeEdge();
  if (controller && h > 0.0)
  {
    // The slab and its halo only: a rank never asks for the whole image.
    const vtkCBC3DPieces::SlabPlan plan = vtkCBC3DPieces::PlanSlabs(whole, this->InformationSpacing, h,
      this->RankHalo, controller->GetNumberOfProcesses(), controller->GetLocalProcessId(), this->SlabWeights(inInfo));
    vtkCBC3DPieces::PieceExtent(plan, whole, extent);
  }
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent, 6);
  // The slab is asked for by extent, not as a piece: a reader that can only give the whole
  // image gives it on every rank (not on the first alone), and the executive crops it.
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::EXACT_EXTENT(), 1);
  // Ghost tets are made here (AddGhostCells), not from ghost voxels.
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  return 1;
}

std::vector<double> vtkCBC3DMesher::SlabWeights(vtkInformation* inputInfo) const
{
  return this->BalanceTissue ? vtkCBC3DPieces::BoundaryPerSlice(inputInfo) : std::vector<double>();
}

bool vtkCBC3DMesher::PreparePiece(vtkImageData* image, vtkInformation* inputInfo, Piece& piece)
{
  const bool first = piece.Controller->GetLocalProcessId() == 0;
  if (this->MaximumNumberOfTets > 0)
  {
    if (first)
    {
      vtkErrorMacro(<< "a tet budget (MaximumNumberOfTets) needs the whole mesh on one process; over MPI "
                    << "ranks give a lattice edge length instead");
    }
    return false;
  }
  int whole[6];
  inputInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  const double h = this->EdgeLength > 0.0 ? this->EdgeLength : this->AutomaticLatticeEdge();
  piece.Plan = vtkCBC3DPieces::PlanSlabs(whole, image->GetSpacing(), h, this->RankHalo,
    piece.Controller->GetNumberOfProcesses(), piece.Controller->GetLocalProcessId(), this->SlabWeights(inputInfo));
  vtkDataArray* labels = vtkCBC3DConvert::ChooseLabelArray(this->GetInputArrayInformation(0), image);
  int lower[3], upper[3];
  piece.HasTissue = labels && vtkCBC3DPieces::TissueBox(image, labels, this->BackgroundLabels, lower, upper);
  if (!vtkCBC3DPieces::AgreeOnTissueBox(
        piece.Controller, piece.HasTissue, lower, upper, piece.WholeLower, piece.WholeUpper))
  {
    if (first)
    {
      vtkErrorMacro(<< "the image has no tissue: every voxel holds a background label");
    }
    return false;
  }
  // Every rank frames its lattice on the whole image's tissue box (vtkCBC3DConvert reads it).
  vtkNew<vtkIntArray> box;
  box->SetName(vtkCBC3DArrayNames::LatticeBox);
  for (const int* bound : { piece.WholeLower, piece.WholeUpper })
  {
    for (int a = 0; a < 3; ++a)
    {
      box->InsertNextValue(bound[a]);
    }
  }
  vtkNew<vtkFieldData> fields;
  fields->ShallowCopy(image->GetFieldData());
  fields->AddArray(box);
  image->SetFieldData(fields);
  return true;
}

bool vtkCBC3DMesher::FinishStage(const char* name, const std::string& error, Piece* piece)
{
  if (!error.empty())
  {
    // Keep the stage's own words: VTK formats "... Class (0x...): message".
    const std::size_t marker = error.find("): ");
    vtkErrorMacro(<< name << ": " << (marker == std::string::npos ? error : error.substr(marker + 3)));
  }
  // A rank that failed stops every rank, here and not in a later exchange that would wait.
  return piece ? vtkCBC3DPieces::AllAgree(piece->Controller, error.empty()) : error.empty();
}

int vtkCBC3DMesher::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  vtkNew<vtkImageData> image;
  image->ShallowCopy(vtkImageData::GetData(inputVector[0]));
  Piece piece;
  piece.Controller = RankController(outputVector->GetInformationObject(0));
  if (piece.Controller && !this->PreparePiece(image, inputVector[0]->GetInformationObject(0), piece))
  {
    output->Initialize();
    return 0;
  }
  bool done = this->RunStages(image, piece.Controller ? &piece : nullptr, output);
  if (done && piece.Controller)
  {
    done = vtkCBC3DPieces::AddGhostCells(piece.Controller, outputVector->GetInformationObject(0), output);
  }
  this->SetProgressText(nullptr);
  if (!done)
  {
    output->Initialize();
  }
  return done ? 1 : 0;
}

bool vtkCBC3DMesher::RunStages(vtkImageData* image, Piece* piece, vtkUnstructuredGrid* output)
{
  vtkNew<vtkCBC3DBCCLattice> lattice;
  vtkNew<vtkCBC3DRefinement> refinement;
  vtkNew<vtkCBC3DDeformation> deformation;
  vtkNew<vtkCBC3DMeshQuality> quality;
  this->ConfigureStages(lattice, refinement, deformation);
  if (piece)
  {
    piece->Passes = vtkCBC3DPieces::MakeRankPasses(piece->Controller, piece->Plan, image);
    refinement->SetRankPasses(piece->Passes);
  }
  vtkInformation* arrayRequest = this->GetInputArrayInformation(0);
  const char* arrayName = arrayRequest && arrayRequest->Has(vtkDataObject::FIELD_NAME())
    ? arrayRequest->Get(vtkDataObject::FIELD_NAME())
    : nullptr;

  const std::vector<Stage> stages = ChooseStages(lattice, refinement, deformation, quality, this->Iterations > 0);
  // Over ranks, the lattice points get their global ids and each rank keeps its own tets before
  // deformation moves them (vtkCBC3DRankDeformation).
  const std::size_t namedStage = stages.size() - (this->Iterations > 0 ? 3 : 2);

  bool meshes = !piece || piece->HasTissue;
  vtkSmartPointer<vtkUnstructuredGrid> current = vtkSmartPointer<vtkUnstructuredGrid>::New();
  double shift = 0.0;
  const double total =
    std::accumulate(stages.begin(), stages.end(), 0.0, [](double sum, const Stage& stage) { return sum + stage.Share; });
  for (std::size_t s = 0; s < stages.size(); ++s)
  {
    vtkCBC3DAlgorithm* filter = stages[s].Filter;
    this->PrepareStage(filter, arrayName, s > 0);
    if (s > 0)
    {
      filter->SetInputData(0, current);
      filter->SetInputData(1, image);
    }
    else
    {
      filter->SetInputData(0, image);
    }
    std::string error;
    const bool acrossRanks = piece && filter == deformation.GetPointer();
    if (acrossRanks)
    {
      error = this->DeformPiece(current, image, deformation, piece, shift / total, stages[s].Share / total);
    }
    else if (meshes)
    {
      error = this->RunStage(filter, stages[s].Name, shift / total, stages[s].Share / total);
    }
    else if (piece && filter == refinement.GetPointer())
    {
      cbc3d::RefineWithoutTissue(*piece->Passes, refinement->AsksForRefinement(),
        refinement->GetBoundaryDistance() >= 0.0, refinement->GetSoundLabels());
    }
    if (this->CheckAbort() && !piece)
    {
      output->Initialize();
      return true;
    }
    if (!this->FinishStage(stages[s].Name, error, piece))
    {
      return false;
    }
    if (meshes && !acrossRanks)
    {
      current = vtkUnstructuredGrid::SafeDownCast(filter->GetOutputDataObject(0));
    }
    if (piece && s == namedStage)
    {
      if (!this->NamePiecePoints(image, lattice, current, piece) || !this->KeepOwnTets(current, piece))
      {
        return false;
      }
      // A rank that owns no tet has nothing to measure: an empty piece, without the empty
      // arrays that ParaView's data movement cannot read back.
      meshes = meshes && current->GetNumberOfCells() > 0;
      // The piece's lattice and refined mesh, halo and all, are done with: free them before
      // deformation builds its own structures.
      std::for_each(stages.begin(), stages.begin() + s + 1,
        [](const Stage& done) { done.Filter->GetOutputDataObject(0)->Initialize(); });
    }
    if (piece && s + 2 == stages.size())
    {
      current->GetPointData()->RemoveArray(vtkCBC3DPieces::LatticeKeyName);
    }
    shift += stages[s].Share;
  }
  if (meshes)
  {
    output->ShallowCopy(quality->GetOutput());
  }
  return true;
}

void vtkCBC3DMesher::ConfigureStages(
  vtkCBC3DBCCLattice* lattice, vtkCBC3DRefinement* refinement, vtkCBC3DDeformation* deformation) const
{
  lattice->SetEdgeLength(this->EdgeLength);
  refinement->SetFidelity(this->Fidelity);
  refinement->SetBoundaryDistance(this->BoundaryDistance);
  refinement->SetMinimumEdgeLength(this->MinimumEdgeLength);
  this->CopySizeControlsTo(lattice);
  this->CopySizeControlsTo(refinement);
  this->CopySizeControlsTo(deformation);
  deformation->SetIterations(this->Iterations);
  deformation->SetPattern(this->Pattern);
  deformation->SetTargetPlacement(this->TargetPlacement);
  deformation->SetKeepVolumes(this->KeepVolumes);
}

void vtkCBC3DMesher::PrepareStage(vtkCBC3DAlgorithm* filter, const char* arrayName, bool imageOnPort1) const
{
  filter->RemoveAllBackgroundLabels();
  for (const vtkTypeInt64 label : this->BackgroundLabels)
  {
    filter->AddBackgroundLabel(label);
  }
  filter->SetNumberOfThreads(this->NumberOfThreads);
  if (arrayName && *arrayName)
  {
    filter->SetInputArrayToProcess(0, imageOnPort1 ? 1 : 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, arrayName);
  }
}

std::string vtkCBC3DMesher::RunStage(vtkAlgorithm* filter, const char* name, double shift, double scale)
{
  StageRelay relay{ this, shift, scale };
  vtkNew<vtkCallbackCommand> forward;
  forward->SetCallback(&StageRelay::Forward);
  forward->SetClientData(&relay);
  const unsigned long progress = filter->AddObserver(vtkCommand::ProgressEvent, forward);
  vtkNew<ErrorRelay> errors;
  const unsigned long failures = filter->AddObserver(vtkCommand::ErrorEvent, errors);
  this->SetProgressText(name);
  filter->Update();
  filter->RemoveObserver(progress);
  filter->RemoveObserver(failures);
  return errors->Message;
}

bool vtkCBC3DMesher::NamePiecePoints(vtkImageData* image, vtkAlgorithm* lattice, vtkUnstructuredGrid* mesh, Piece* piece)
{
  std::string error;
  vtkDataArray* edge = lattice->GetOutputDataObject(0)->GetFieldData()->GetArray(vtkCBC3DArrayNames::LatticeEdgeLength);
  if (piece->HasTissue && edge)
  {
    const double h = edge->GetComponent(0, 0);
    piece->LatticeEdge = h;
    const vtkCBC3DPieces::LatticeKeys keys(image, piece->WholeLower, h);
    const int axis = piece->Plan.Axis;
    piece->CutKeys.clear();
    for (int r = 1; r < piece->Plan.Pieces; ++r)
    {
      piece->CutKeys.push_back(keys.CutKey(axis, piece->Plan.Cuts[r], image->GetSpacing()[axis]));
    }
    vtkCBC3DPieces::AddLatticeKeys(mesh, keys, error);
  }
  return this->FinishStage("Global point ids", error, piece);
}

bool vtkCBC3DMesher::KeepOwnTets(vtkSmartPointer<vtkUnstructuredGrid>& mesh, Piece* piece)
{
  vtkNew<vtkUnstructuredGrid> owned;
  std::string error;
  vtkCBC3DSeams::SeamReport report;
  if (!vtkCBC3DSeams::KeepOwnedTets(
        piece->Controller, piece->Plan.Axis, piece->CutKeys, mesh, owned, report, error))
  {
    if (piece->Controller->GetLocalProcessId() == 0)
    {
      vtkErrorMacro(<< error);
    }
    return false;
  }
  mesh = owned;
  return true;
}

std::string vtkCBC3DMesher::DeformPiece(vtkUnstructuredGrid* mesh, vtkImageData* image,
  vtkCBC3DDeformation* deformation, Piece* piece, double shift, double scale)
{
  vtkCBC3DRankDeformation::Layout layout;
  layout.Axis = piece->Plan.Axis;
  layout.Cuts = piece->Plan.Cuts;
  layout.CutKeys = piece->CutKeys;
  layout.Cube = piece->LatticeEdge;
  auto run = [&](vtkUnstructuredGrid* part, vtkImageData* slices, vtkPoints* moved) {
    deformation->SetInputData(0, part);
    deformation->SetInputData(1, slices);
    const std::string error = this->RunStage(deformation, "Deformation", shift, scale);
    vtkPointSet* output = vtkPointSet::SafeDownCast(deformation->GetOutputDataObject(0));
    if (!error.empty() || !output || output->GetNumberOfPoints() != part->GetNumberOfPoints())
    {
      return error.empty() ? std::string("the deformation was stopped") : error;
    }
    moved->SetDataTypeToDouble(); // (a deep copy keeps the receiver's type)
    moved->DeepCopy(output->GetPoints());
    return error;
  };
  std::string error;
  vtkDataArray* labels = vtkCBC3DConvert::ChooseLabelArray(this->GetInputArrayInformation(0), image);
  vtkCBC3DRankDeformation::DeformAcrossRanks(piece->Controller, layout, image, labels, mesh, run, error);
  return error;
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
  os << indent << "RankHalo: " << this->RankHalo << " lattice cubes\n";
}
