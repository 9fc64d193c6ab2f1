#include "VtuWriter.h"

#include "VtuPayload.h"

#include "cbc3d/base/Parallel.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationDoubleVectorKey.h>
#include <vtkInformationIterator.h>
#include <vtkNew.h>
#include <vtkNumberToString.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <locale>
#include <sstream>
#include <type_traits>
#include <vector>

namespace
{
// VTK's type names for the plain numeric arrays (vtkXMLWriter::GetWordTypeName); nullptr for
// the rest (bits, strings, ...), which we leave to VTK's writer.
const char* WordTypeName(int type)
{
  switch (type)
  {
    case VTK_FLOAT: return "Float32";
    case VTK_DOUBLE: return "Float64";
    case VTK_ID_TYPE: return sizeof(vtkIdType) == 8 ? "Int64" : nullptr; // with IdType="1"
    case VTK_CHAR: return std::is_signed<char>::value ? "Int8" : "UInt8";
    case VTK_SIGNED_CHAR: return "Int8";
    case VTK_UNSIGNED_CHAR: return "UInt8";
    case VTK_SHORT: return "Int16";
    case VTK_UNSIGNED_SHORT: return "UInt16";
    case VTK_INT: return "Int32";
    case VTK_UNSIGNED_INT: return "UInt32";
    case VTK_LONG: return sizeof(long) == 8 ? "Int64" : "Int32";
    case VTK_UNSIGNED_LONG: return sizeof(long) == 8 ? "UInt64" : "UInt32";
    case VTK_LONG_LONG: return "Int64";
    case VTK_UNSIGNED_LONG_LONG: return "UInt64";
    default: return nullptr;
  }
}

// min and max of a big integer array on threads: exact in any order (floats are not: NaN, -0),
// so the same as VTK's GetRange(-1), which takes one thread.
template <typename T>
void IntegerRange(const T* values, vtkIdType count, int threads, double range[2])
{
  T low = values[0], high = values[0];
#pragma omp parallel for reduction(min : low) reduction(max : high) num_threads(threads)
  for (vtkIdType i = 0; i < count; ++i)
  {
    low = std::min(low, values[i]);
    high = std::max(high, values[i]);
  }
  range[0] = static_cast<double>(low);
  range[1] = static_cast<double>(high);
}

// The range vtkXMLWriter writes: VTK's GetRange(-1), which caches it in the array (a vector's
// L2_NORM_RANGE, written as an information key), but for big one-component integer arrays.
void Range(vtkDataArray* array, int threads, double range[2])
{
  const vtkIdType count = array->GetNumberOfValues();
  if (array->GetNumberOfComponents() == 1 && count >= 32768 && threads > 1)
  {
    switch (array->GetDataType())
    {
      vtkTemplateMacro(if constexpr (std::is_integral<VTK_TT>::value) {
        IntegerRange(static_cast<const VTK_TT*>(array->GetVoidPointer(0)), count, threads, range);
        return;
      });
    }
  }
  array->GetRange(range, -1);
}

// Information keys vtkXMLWriter::WriteInformation writes that we do not: we give up on them.
bool IsUnwrittenKeyVtkWrites(vtkInformationKey* key)
{
  for (const char* type : { "vtkInformationDoubleKey", "vtkInformationIdTypeKey",
         "vtkInformationIntegerKey", "vtkInformationIntegerVectorKey", "vtkInformationStringKey",
         "vtkInformationStringVectorKey", "vtkInformationUnsignedLongKey",
         "vtkInformationQuadratureSchemeDefinitionVectorKey" })
    if (key->IsA(type))
      return true;
  return false;
}

// The document as texts between the arrays' binary payloads.
class VtuDocument
{
public:
  explicit VtuDocument(int threads)
    : Threads(cbc3d::ThreadCount(threads))
  {
    this->Text.imbue(std::locale::classic());
    this->Text.precision(11); // vtkXMLWriter's stream precision
  }
  bool Build(vtkUnstructuredGrid* mesh);
  std::string Join()
  {
    this->Texts.push_back(this->Text.str());
    return JoinVtuPayloads(this->Texts, this->Payloads, this->Threads);
  }

private:
  std::ostream& Indent(int n) { return this->Text << std::string(n, ' '); }
  void FieldData(vtkFieldData* fields);
  void Attributes(const char* element, vtkDataSetAttributes* data);
  bool Cells(vtkUnstructuredGrid* mesh);
  template <typename Ids>
  bool CellArrays(vtkUnstructuredGrid* mesh, Ids* connectivity, Ids* offsets);
  void Array(vtkAbstractArray* array, int indent, const std::string& name, bool tuples);
  void Information(vtkInformation* info, int indent);
  void DoubleVector(vtkInformationDoubleVectorKey* key, vtkInformation* info, int indent);
  static std::string NameOf(vtkAbstractArray* array);

  const int Threads;
  std::ostringstream Text;
  std::vector<std::string> Texts;
  std::vector<VtuBytes> Payloads;
  bool Supported = true;
};

// Arrays without a name get one from their address, as VTK's writer names them.
std::string VtuDocument::NameOf(vtkAbstractArray* array)
{
  if (array->GetName())
    return array->GetName();
  std::ostringstream name;
  name << "Array " << static_cast<void*>(array);
  return name.str();
}

bool VtuDocument::Build(vtkUnstructuredGrid* mesh)
{
  vtkInformation* meta = mesh->GetInformation();
  if (mesh->GetFaces() || !mesh->GetPoints() || !mesh->GetCells() ||
    !mesh->GetCellTypesArray() || (meta && meta->Has(vtkDataObject::DATA_TIME_STEP())))
    return false; // polyhedra, no points or cells, a time value: VTK's writer does these
  this->Text << "<?xml version=\"1.0\"?>\n"
             << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\""
             << " header_type=\"UInt32\" compressor=\"vtkZLibDataCompressor\">\n"
             << "  <UnstructuredGrid>\n";
  this->FieldData(mesh->GetFieldData());
  this->Text << "    <Piece NumberOfPoints=\"" << mesh->GetNumberOfPoints()
             << "\" NumberOfCells=\"" << mesh->GetNumberOfCells() << "\">\n";
  this->Attributes("PointData", mesh->GetPointData());
  this->Attributes("CellData", mesh->GetCellData());
  this->Text << "      <Points>\n";
  this->Array(mesh->GetPoints()->GetData(), 8, NameOf(mesh->GetPoints()->GetData()), false);
  this->Text << "      </Points>\n";
  if (!this->Cells(mesh))
    return false;
  this->Text << "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return this->Supported;
}

void VtuDocument::FieldData(vtkFieldData* fields)
{
  if (!fields || fields->GetNumberOfArrays() == 0)
    return;
  this->Text << "    <FieldData>\n";
  for (int i = 0; i < fields->GetNumberOfArrays(); ++i)
    this->Array(fields->GetAbstractArray(i), 6, NameOf(fields->GetAbstractArray(i)), true);
  this->Text << "    </FieldData>\n";
}

// Point or cell data: the active attributes (Scalars="Label") on the element, then the arrays;
// an unnamed active array is called after its attribute ("Scalars_"), as VTK names it.
void VtuDocument::Attributes(const char* element, vtkDataSetAttributes* data)
{
  std::vector<std::string> names(data->GetNumberOfArrays());
  for (int i = 0; i < data->GetNumberOfArrays(); ++i)
    names[i] = NameOf(data->GetAbstractArray(i));
  this->Indent(6) << "<" << element;
  int active[vtkDataSetAttributes::NUM_ATTRIBUTES];
  data->GetAttributeIndices(active);
  for (int a = 0; a < vtkDataSetAttributes::NUM_ATTRIBUTES; ++a)
  {
    if (active[a] < 0)
      continue;
    const char* attribute = vtkDataSetAttributes::GetAttributeTypeAsString(a);
    if (!data->GetAbstractArray(active[a])->GetName())
      names[active[a]] = std::string(attribute) + "_";
    this->Text << " " << attribute << "=\"" << names[active[a]] << "\"";
  }
  this->Text << ">\n";
  for (int i = 0; i < data->GetNumberOfArrays(); ++i)
    this->Array(data->GetAbstractArray(i), 8, names[i], false);
  this->Indent(6) << "</" << element << ">\n";
}

// Connectivity, offsets without the leading 0, and types, as VTK 9's writer converts them; the
// arrays are views on the mesh's own, so that their ranges are cached on the views.
bool VtuDocument::Cells(vtkUnstructuredGrid* mesh)
{
  vtkCellArray* cells = mesh->GetCells();
  return cells->IsStorage64Bit()
    ? this->CellArrays(mesh, cells->GetConnectivityArray64(), cells->GetOffsetsArray64())
    : this->CellArrays(mesh, cells->GetConnectivityArray32(), cells->GetOffsetsArray32());
}

template <typename Ids>
bool VtuDocument::CellArrays(vtkUnstructuredGrid* mesh, Ids* connectivity, Ids* offsets)
{
  vtkUnsignedCharArray* types = mesh->GetCellTypesArray();
  const vtkIdType count = mesh->GetNumberOfCells();
  if (offsets->GetNumberOfValues() != count + 1 || types->GetNumberOfValues() != count)
    return false;
  vtkNew<Ids> points, ends;
  vtkNew<vtkUnsignedCharArray> kinds;
  points->SetArray(connectivity->GetPointer(0), connectivity->GetNumberOfValues(), 1);
  ends->SetArray(offsets->GetPointer(1), count, 1);
  kinds->SetArray(types->GetPointer(0), count, 1);
  this->Text << "      <Cells>\n";
  this->Array(points, 8, "connectivity", false);
  this->Array(ends, 8, "offsets", false);
  this->Array(kinds, 8, "types", false);
  this->Text << "      </Cells>\n";
  return true;
}

// One <DataArray>: vtkXMLWriter::WriteArrayInline's attributes, the range of the values (of
// the vectors' magnitudes) in VTK's shortest round-trip format, the data, the information keys.
void VtuDocument::Array(vtkAbstractArray* abstract, int indent, const std::string& name, bool tuples)
{
  vtkDataArray* array = vtkDataArray::SafeDownCast(abstract);
  const char* type = array ? WordTypeName(array->GetDataType()) : nullptr;
  if (!type || !array->HasStandardMemoryLayout())
  {
    this->Supported = false;
    return;
  }
  this->Indent(indent) << "<DataArray type=\"" << type << "\"";
  if (array->GetDataType() == VTK_ID_TYPE)
    this->Text << " IdType=\"1\"";
  this->Text << " Name=\"" << name << "\"";
  if (array->GetNumberOfComponents() > 1)
    this->Text << " NumberOfComponents=\"" << array->GetNumberOfComponents() << "\"";
  for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    if (const char* component = array->GetComponentName(c))
      this->Text << " ComponentName" << c << "=\"" << component << "\"";
  if (tuples)
    this->Text << " NumberOfTuples=\"" << array->GetNumberOfTuples() << "\"";
  double range[2];
  Range(array, this->Threads, range);
  const vtkNumberToString format;
  this->Text << " format=\"binary\" RangeMin=\"" << format(range[0]) << "\" RangeMax=\""
             << format(range[1]) << "\">\n";
  this->Indent(indent + 2);
  this->Texts.push_back(this->Text.str());
  this->Text.str("");
  this->Payloads.push_back({ static_cast<const unsigned char*>(array->GetVoidPointer(0)),
    static_cast<std::size_t>(array->GetNumberOfValues()) * array->GetDataTypeSize() });
  this->Text << "\n";
  vtkInformation* info = array->GetInformation();
  if (info && info->GetNumberOfKeys() > 0)
    this->Information(info, indent);
  this->Indent(indent) << "</DataArray>\n";
}

// The keys VTK serializes, in its iterator's order: only double vectors (the cached L2_NORM_RANGE
// of vectors) are written here; a key of another written kind sends the mesh to VTK's writer.
void VtuDocument::Information(vtkInformation* info, int indent)
{
  vtkNew<vtkInformationIterator> keys;
  keys->SetInformationWeak(info);
  for (keys->InitTraversal(); vtkInformationKey* key = keys->GetCurrentKey(); keys->GoToNextItem())
  {
    if (auto* vector = vtkInformationDoubleVectorKey::SafeDownCast(key))
      this->DoubleVector(vector, info, indent + 2);
    else if (IsUnwrittenKeyVtkWrites(key))
      this->Supported = false;
  }
}

// vtkXMLDataElement::PrintXML's layout; values as a stream at precision 11 prints them.
void VtuDocument::DoubleVector(vtkInformationDoubleVectorKey* key, vtkInformation* info, int indent)
{
  const int length = key->Length(info);
  if (length == 0)
  {
    this->Supported = false; // an empty element, printed short: not worth the code
    return;
  }
  this->Indent(indent) << "<InformationKey name=\"" << key->GetName() << "\" location=\""
                       << key->GetLocation() << "\" length=\"" << length << "\">\n";
  for (int i = 0; i < length; ++i)
  {
    std::ostringstream value;
    value.precision(11);
    value << key->Get(info, i);
    this->Indent(indent + 2) << "<Value index=\"" << i << "\">\n";
    this->Indent(indent + 4) << value.str() << "\n";
    this->Indent(indent + 2) << "</Value>\n";
  }
  this->Indent(indent) << "</InformationKey>\n";
}
} // namespace

bool MakeVtuBytes(vtkUnstructuredGrid* mesh, int threads, std::string& bytes)
{
  VtuDocument document(threads);
  if (!document.Build(mesh))
    return false;
  bytes = document.Join();
  return true;
}
