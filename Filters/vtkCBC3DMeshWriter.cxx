#include "vtkCBC3DMeshWriter.h"

#include "vtkCBC3DConvert.h"

#include "cbc3d/export/MeshExport.h"

#include <vtkInformation.h>
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

void vtkCBC3DMeshWriter::WriteData()
{
  const std::string path = this->FileName ? this->FileName : "";
  if (!cbc3d::IsExportExtension(cbc3d::LowerCaseExtension(path)))
  {
    vtkErrorMacro(<< "unknown extension for '" << path << "': use " << cbc3d::ExportExtensions());
    return;
  }
  cbc3d::TaggedMesh tagged;
  std::string error;
  if (!vtkCBC3DConvert::ToTaggedMesh(vtkUnstructuredGrid::SafeDownCast(this->GetInput()), this->OutsideLabel, tagged, error))
  {
    vtkErrorMacro(<< error);
    return;
  }
  const cbc3d::Status status = cbc3d::WriteExportFile(tagged, path, this->MshVersion22);
  if (!status.IsOk())
  {
    vtkErrorMacro(<< status.GetMessage());
  }
}
