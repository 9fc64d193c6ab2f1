#include "vtkCBC3DMeshWriter.h"

#include "vtkCBC3DConvert.h"
#include "vtkCBC3DGatherPieces.h"

#include "cbc3d/export/MeshExport.h"

#include <vtkInformation.h>
#include <vtkMultiProcessController.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkUnstructuredGrid.h>

vtkStandardNewMacro(vtkCBC3DMeshWriter);

vtkCBC3DMeshWriter::~vtkCBC3DMeshWriter()
{
  this->SetFileName(nullptr);
}

void vtkCBC3DMeshWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "MshVersion22: " << this->MshVersion22 << "\n";
  os << indent << "OutsideLabel: " << this->OutsideLabel << "\n";
}

int vtkCBC3DMeshWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  return 1;
}

namespace
{
// Writes one mesh to `path`; the error, if any, in `error`.
void WriteMesh(vtkUnstructuredGrid* mesh, const std::string& path, vtkTypeInt64 outside, bool msh22, std::string& error)
{
  cbc3d::TaggedMesh tagged;
  if (!vtkCBC3DConvert::ToTaggedMesh(mesh, outside, tagged, error))
  {
    return;
  }
  const cbc3d::Status status = cbc3d::WriteExportFile(tagged, path, msh22);
  if (!status.IsOk())
  {
    error = status.GetMessage();
  }
}
} // namespace

vtkTypeBool vtkCBC3DMeshWriter::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()) && controller &&
    controller->GetNumberOfProcesses() > 1)
  {
    // Each rank asks for its own piece, which WriteData gathers: the mesher then meshes a
    // slab per rank, not the whole image on every rank.
    vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), controller->GetLocalProcessId());
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), controller->GetNumberOfProcesses());
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    return 1;
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

void vtkCBC3DMeshWriter::WriteData()
{
  const std::string path = this->FileName ? this->FileName : "";
  if (!cbc3d::IsExportExtension(cbc3d::LowerCaseExtension(path)))
  {
    vtkErrorMacro(<< "unknown extension for '" << path << "': use " << cbc3d::ExportExtensions());
    return;
  }
  auto* input = vtkUnstructuredGrid::SafeDownCast(this->GetInput());
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  std::string error;
  if (!controller || controller->GetNumberOfProcesses() < 2)
  {
    WriteMesh(input, path, this->OutsideLabel, this->MshVersion22, error);
    if (!error.empty())
    {
      vtkErrorMacro(<< error);
    }
    return;
  }
  // Under MPI: rank 0 merges the pieces and writes one file (atomically: whole or not at
  // all); every rank learns whether it did, and rank 0 alone says why not.
  vtkSmartPointer<vtkUnstructuredGrid> whole;
  vtkCBC3DGatherPieces::Gather(controller, input, whole, error);
  const bool first = controller->GetLocalProcessId() == 0;
  if (first && whole)
  {
    WriteMesh(whole, path, this->OutsideLabel, this->MshVersion22, error);
  }
  int written = first && error.empty() ? 1 : 0;
  controller->Broadcast(&written, 1, 0);
  if (first && !error.empty())
  {
    vtkErrorMacro(<< error);
  }
  if (!written)
  {
    this->SetErrorCode(1);
  }
}
