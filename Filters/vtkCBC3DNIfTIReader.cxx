#include "vtkCBC3DNIfTIReader.h"

#include "vtkCBC3DNIfTIFiles.h"
#include "vtkCBC3DNIfTIGzipVoxels.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationDoubleVectorKey.h>
#include <vtkInformationVector.h>
#include <vtkMatrix4x4.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkNIFTIImageHeader.h>
#include <vtkNIFTIImageReader.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <vtk_zlib.h>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCBC3DNIfTIReader);
vtkInformationKeyMacro(vtkCBC3DNIfTIReader, BOUNDARY_PER_SLICE, DoubleVector);

namespace
{
// zlib's largest expansion: a deflate stream of n bytes inflates to at most 1032 n bytes. A
// header that claims more voxel bytes than that is corrupt, and trusting it would make the
// inner reader allocate the claimed size (a 480-byte file claiming 30000^3 voxels aborted the
// cbc3d command in operator new).
constexpr double LargestInflation = 1032.0;
} // namespace

bool vtkCBC3DNIfTIReader::VoxelsFitInFile()
{
  int extent[6];
  this->Reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  if (extent[1] < extent[0] || extent[3] < extent[2] || extent[5] < extent[4])
  {
    // vtkNIFTIImageReader would go on to read into an empty image (a header with dim[3] = 0
    // made it write past its buffer: found by the NIfTI fuzzer).
    vtkErrorMacro(<< "Cannot read NIfTI file " << this->FileName
                  << ": its header gives an image with no voxels along an axis");
    return false;
  }
  double claimed = this->Reader->GetNumberOfScalarComponents() *
    double(vtkDataArray::GetDataTypeSize(this->Reader->GetDataScalarType()));
  for (int a = 0; a < 3; ++a)
  {
    claimed *= double(extent[2 * a + 1]) - extent[2 * a] + 1.0;
  }
  const std::string voxelFile = vtkCBC3DNIfTIFiles::VoxelFileName(this->FileName);
  const double fileBytes = voxelFile.empty() ? 0.0 : double(vtksys::SystemTools::FileLength(voxelFile));
  if (voxelFile.empty() || claimed <= LargestInflation * fileBytes)
  {
    return true;
  }
  vtkErrorMacro(<< "Cannot read NIfTI file " << this->FileName << ": its header claims "
                << extent[1] - extent[0] + 1 << " x " << extent[3] - extent[2] + 1 << " x "
                << extent[5] - extent[4] + 1 << " voxels (" << claimed
                << " bytes), more than its " << fileBytes << " bytes of data can hold");
  return false;
}

namespace
{
// Messages that the inner reader (and its executive) reported during one pass.
struct ReaderMessages
{
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
  vtkAlgorithm* Owner = nullptr;
};

// Strip VTK's "ClassName (0x...): " prefix and trailing newlines from a message.
std::string StripMessage(const char* text)
{
  std::string message = text ? text : "";
  const std::string::size_type prefix = message.find("): ");
  if (prefix != std::string::npos)
  {
    message = message.substr(prefix + 3);
  }
  while (!message.empty() && (message.back() == '\n' || message.back() == '\r'))
  {
    message.pop_back();
  }
  return message;
}

void CollectMessage(vtkObject*, unsigned long event, void* clientData, void* callData)
{
  ReaderMessages* messages = static_cast<ReaderMessages*>(clientData);
  const std::string text = StripMessage(static_cast<const char*>(callData));
  if (event == vtkCommand::ErrorEvent)
  {
    messages->Errors.push_back(text);
  }
  else if (event == vtkCommand::WarningEvent)
  {
    messages->Warnings.push_back(text);
  }
  else if (event == vtkCommand::ProgressEvent && messages->Owner && callData)
  {
    messages->Owner->UpdateProgress(*static_cast<double*>(callData));
  }
}
} // namespace

vtkCBC3DNIfTIReader::vtkCBC3DNIfTIReader()
  : Reader(vtkNIFTIImageReader::New())
{
  this->SetNumberOfInputPorts(0);
}

vtkCBC3DNIfTIReader::~vtkCBC3DNIfTIReader()
{
  this->SetFileName(nullptr);
  this->Reader->Delete();
}

int vtkCBC3DNIfTIReader::CanReadFile(const char* filename)
{
  if (!filename || !vtksys::SystemTools::FileExists(filename, true))
  {
    return 0;
  }
  return this->Reader->CanReadFile(filename);
}

bool vtkCBC3DNIfTIReader::RunReader(const int* extent)
{
  ReaderMessages messages;
  messages.Owner = extent ? this : nullptr;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(CollectMessage);
  callback->SetClientData(&messages);
  vtkExecutive* executive = this->Reader->GetExecutive();
  const unsigned long readerErrors = this->Reader->AddObserver(vtkCommand::ErrorEvent, callback);
  const unsigned long readerWarnings =
    this->Reader->AddObserver(vtkCommand::WarningEvent, callback);
  const unsigned long readerProgress =
    this->Reader->AddObserver(vtkCommand::ProgressEvent, callback);
  const unsigned long executiveErrors = executive->AddObserver(vtkCommand::ErrorEvent, callback);

  vtkStreamingDemandDrivenPipeline* sddp =
    vtkStreamingDemandDrivenPipeline::SafeDownCast(executive);
  int ok = 0;
  if (sddp)
  {
    ok = extent ? this->Reader->UpdateExtent(extent) : sddp->UpdateInformation();
  }

  this->Reader->RemoveObserver(readerErrors);
  this->Reader->RemoveObserver(readerWarnings);
  this->Reader->RemoveObserver(readerProgress);
  executive->RemoveObserver(executiveErrors);

  for (const std::string& warning : messages.Warnings)
  {
    vtkWarningMacro(<< this->FileName << ": " << warning);
  }
  if (!ok || !messages.Errors.empty())
  {
    // The reader's own error comes first; the executive's "returned failure" adds nothing.
    const std::string reason =
      messages.Errors.empty() ? std::string("vtkNIFTIImageReader failed") : messages.Errors[0];
    vtkErrorMacro(<< "Cannot read NIfTI file " << this->FileName << ": " << reason);
    return false;
  }
  return true;
}

bool vtkCBC3DNIfTIReader::ComputeFrame()
{
  vtkMatrix4x4* sform = this->Reader->GetSFormMatrix(); // only when sform_code > 0
  vtkMatrix4x4* qform = this->Reader->GetQFormMatrix(); // only when qform_code > 0
  const double tolerance = 1e-4;

  vtkMatrix4x4* frame = nullptr;
  if (sform)
  {
    const double error = vtkCBC3DNIfTIFiles::OrthonormalityError(sform);
    if (error <= tolerance)
    {
      frame = sform;
      this->FrameSource = "sform";
    }
    else if (qform)
    {
      vtkWarningMacro(<< this->FileName << ": the sform holds a shear or a scaling besides the "
                      << "voxel size (deviation from orthonormal " << error
                      << "); using the qform instead");
      frame = qform;
      this->FrameSource = "qform";
    }
    else
    {
      vtkErrorMacro(<< "Cannot place NIfTI file " << this->FileName
                    << ": its sform holds a shear or a scaling besides the voxel size "
                    << "(deviation from orthonormal " << error << ") and it has no qform");
      return false;
    }
  }
  else if (qform)
  {
    frame = qform;
    this->FrameSource = "qform";
  }
  else
  {
    this->FrameSource = "voxel size";
  }

  this->Reader->GetDataSpacing(this->Spacing);
  for (int r = 0; r < 3; ++r)
  {
    this->Origin[r] = frame ? frame->GetElement(r, 3) : 0.0;
    for (int c = 0; c < 3; ++c)
    {
      this->Direction[3 * r + c] = frame ? frame->GetElement(r, c) : (r == c ? 1.0 : 0.0);
    }
  }
  // A negative pixdim: keep the positions, make the spacing positive.
  for (int c = 0; c < 3; ++c)
  {
    if (this->Spacing[c] < 0.0)
    {
      this->Spacing[c] = -this->Spacing[c];
      for (int r = 0; r < 3; ++r)
      {
        this->Direction[3 * r + c] = -this->Direction[3 * r + c];
      }
    }
  }
  return true;
}

int vtkCBC3DNIfTIReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  this->FrameSource.clear();
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "No NIfTI file name set");
    return 0;
  }
  if (!vtksys::SystemTools::FileExists(this->FileName, true))
  {
    vtkErrorMacro(<< "Cannot read NIfTI file " << this->FileName << ": no such file");
    return 0;
  }
  if (!this->Reader->CanReadFile(this->FileName))
  {
    vtkErrorMacro(<< "Cannot read " << this->FileName
                  << ": not a NIfTI file (no NIfTI-1/2 or Analyze 7.5 header)");
    return 0;
  }

  const std::string headerProblem = vtkCBC3DNIfTIFiles::HeaderProblem(vtkCBC3DNIfTIFiles::HeaderFileName(this->FileName));
  if (!headerProblem.empty())
  {
    vtkErrorMacro(<< "Cannot read NIfTI file " << this->FileName << ": " << headerProblem);
    return 0;
  }

  this->Reader->SetFileName(this->FileName);
  if (!this->RunReader(nullptr) || !this->VoxelsFitInFile() || !this->ComputeFrame())
  {
    return 0;
  }

  vtkInformation* readerInfo = this->Reader->GetOutputInformation(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int extent[6];
  readerInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  // Any sub-extent can be read: a parallel pipeline then gives each rank only its piece.
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  outInfo->Set(vtkDataObject::SPACING(), this->Spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), this->Origin, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), this->Direction, 9);
  vtkDataObject::SetPointDataActiveScalarInfo(
    outInfo, this->Reader->GetDataScalarType(), this->Reader->GetNumberOfScalarComponents());
  this->GiveBoundaryPerSlice(outInfo);
  return 1;
}

void vtkCBC3DNIfTIReader::GiveBoundaryPerSlice(vtkInformation* outInfo)
{
  outInfo->Remove(BOUNDARY_PER_SLICE());
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const bool ranks = controller && controller->GetNumberOfProcesses() > 1;
  // (InflateNIfTIVoxels' file order: only where VTK keeps it.)
  if (!(ranks || this->CountBoundaryPerSlice) || this->Reader->GetNumberOfScalarComponents() != 1 ||
    !(this->Reader->GetQFac() > 0))
  {
    return;
  }
  const long time = vtksys::SystemTools::ModifiedTime(this->FileName);
  const unsigned long size = vtksys::SystemTools::FileLength(this->FileName);
  if (this->CountedFile != this->FileName || this->CountedTime != time || this->CountedSize != size)
  {
    int whole[6];
    outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    this->CountedFile = this->FileName;
    this->CountedTime = time;
    this->CountedSize = size;
    if (!CountNIfTIBoundaryPerSlice(this->FileName, this->Reader->GetDataScalarType(), whole, this->BoundaryPerSlice))
    {
      this->BoundaryPerSlice.clear(); // (the read itself reports what is wrong with the file)
    }
  }
  if (!this->BoundaryPerSlice.empty())
  {
    outInfo->Set(BOUNDARY_PER_SLICE(), this->BoundaryPerSlice.data(), int(this->BoundaryPerSlice.size()));
  }
}

bool vtkCBC3DNIfTIReader::ReadVoxels(vtkImageData* output, const int extent[6])
{
  this->InflatedAtOnce = false;
  this->InflatedSubExtent = false;
  const int scalarType = this->Reader->GetDataScalarType();
  if (extent[1] < extent[0] || extent[3] < extent[2] || extent[5] < extent[4])
  {
    // An empty piece (more pieces than the image splits into): no voxels, but the array.
    vtkSmartPointer<vtkDataArray> none = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(scalarType));
    none->SetNumberOfComponents(this->Reader->GetNumberOfScalarComponents());
    none->SetName("NIFTI");
    output->SetExtent(const_cast<int*>(extent));
    output->GetPointData()->SetScalars(none);
    return true;
  }
  int whole[6];
  this->Reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  // InflateNIfTIVoxels keeps the file's slice order: only for images VTK does not reverse.
  if (this->Reader->GetNumberOfScalarComponents() == 1 && this->Reader->GetQFac() > 0)
  {
    if (vtkSmartPointer<vtkDataArray> inflated = InflateNIfTIVoxels(this->FileName, scalarType, whole, extent))
    {
      inflated->SetName("NIFTI"); // vtkNIFTIImageReader's name for them
      output->SetExtent(const_cast<int*>(extent));
      output->GetPointData()->SetScalars(inflated);
      this->InflatedAtOnce = std::equal(extent, extent + 6, whole);
      this->InflatedSubExtent = !this->InflatedAtOnce;
      this->UpdateProgress(1.0);
      return true;
    }
  }
  return this->ReadVoxelsWithReader(output, extent);
}

bool vtkCBC3DNIfTIReader::ReadVoxelsWithReader(vtkImageData* output, const int extent[6])
{
  int whole[6], asked[6];
  this->Reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  std::copy(extent, extent + 6, asked);
  if (this->Reader->GetQFac() < 0)
  {
    // Where it reverses the slices, vtkNIFTIImageReader reverses them within the part it reads:
    // the mirrored part holds our slices in our order, at indices shifted by a constant.
    asked[4] = whole[4] + whole[5] - extent[5];
    asked[5] = whole[4] + whole[5] - extent[4];
  }
  if (!this->RunReader(asked))
  {
    return false;
  }
  vtkImageData* image = this->Reader->GetOutput();
  int read[6];
  image->GetExtent(read);
  if (!image->GetPointData()->GetScalars() || !std::equal(read, read + 6, asked))
  {
    vtkErrorMacro(<< "Cannot read NIfTI file " << this->FileName << ": no voxel values read");
    return false;
  }
  output->ShallowCopy(image);
  output->SetExtent(const_cast<int*>(extent));
  // The voxels are ours alone now, and the next request reads afresh the part it asks.
  image->ReleaseData();
  return true;
}

int vtkCBC3DNIfTIReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector);
  output->Initialize();
  if (this->FrameSource.empty())
  {
    return 0; // RequestInformation failed and said why
  }
  // The asked extent, clamped to the image; the whole image where none is asked.
  int extent[6];
  this->Reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    int asked[6];
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), asked);
    for (int a = 0; a < 3; ++a)
    {
      extent[2 * a] = std::max(extent[2 * a], asked[2 * a]);
      extent[2 * a + 1] = std::min(extent[2 * a + 1], asked[2 * a + 1]);
    }
  }
  if (!this->ReadVoxels(output, extent))
  {
    return 0;
  }
  output->SetSpacing(this->Spacing);
  output->SetOrigin(this->Origin);
  output->SetDirectionMatrix(this->Direction);
  vtkDataArray* scalars = output->GetPointData()->GetScalars();
  if (!scalars->GetName() || !*scalars->GetName())
  {
    scalars->SetName("Labels");
  }
  output->GetPointData()->SetActiveScalars(scalars->GetName());
  return 1;
}

void vtkCBC3DNIfTIReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "FrameSource: " << (this->FrameSource.empty() ? "(none)" : this->FrameSource)
     << "\n";
  os << indent << "InflatedAtOnce: " << this->InflatedAtOnce << "\n";
  os << indent << "InflatedSubExtent: " << this->InflatedSubExtent << "\n";
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << " "
     << this->Origin[2] << "\n";
  os << indent << "Spacing: " << this->Spacing[0] << " " << this->Spacing[1] << " "
     << this->Spacing[2] << "\n";
  os << indent << "Direction:";
  for (const double value : this->Direction)
  {
    os << " " << value;
  }
  os << "\n";
}
