#include "vtkCBC3DConvert.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DLabelValues.h"

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <sstream>

namespace vtkCBC3DConvert
{
vtkDataArray* ChooseLabelArray(vtkInformation* arrayRequest, vtkImageData* image)
{
  if (!image)
  {
    return nullptr;
  }
  vtkPointData* pointData = image->GetPointData();
  const char* name = arrayRequest && arrayRequest->Has(vtkDataObject::FIELD_NAME())
    ? arrayRequest->Get(vtkDataObject::FIELD_NAME())
    : nullptr;
  if (name && *name)
  {
    return pointData->GetArray(name);
  }
  if (vtkDataArray* scalars = pointData->GetScalars())
  {
    return scalars;
  }
  return pointData->GetNumberOfArrays() == 1 ? pointData->GetArray(0) : nullptr;
}

namespace
{
// Stores the codes of the box of the voxels that do not hold the first background label
// (`lower` to `upper`; none: upper[0] < 0), and one voxel around it (the stages read one voxel
// beyond a tissue voxel), clamped to the image: the rest of the image is that background, so a
// padded image costs what its box does. False if a value has no code (the survey that made the
// codes saw every value, so never): the labels are then not all written (they are not zeroed first).
bool StoreLabels(vtkDataArray* labels, std::array<int, 3> lower, std::array<int, 3> upper, cbc3d::LabelImage& out,
  int threads)
{
  const std::array<int, 3>& d = out.Dimensions;
  if (upper[0] < 0)
  {
    lower = { 0, 0, 0 };
    upper = { d[0] - 1, d[1] - 1, d[2] - 1 };
  }
  else
  {
    for (int a = 0; a < 3; ++a)
    {
      lower[a] = std::max(lower[a] - 1, 0);
      upper[a] = std::min(upper[a] + 1, d[a] - 1);
    }
  }
  out.StoredLower = lower;
  out.StoredSize = { upper[0] - lower[0] + 1, upper[1] - lower[1] + 1, upper[2] - lower[2] + 1 };
  out.Labels.resize(std::size_t(out.StoredSize[0]) * out.StoredSize[1] * out.StoredSize[2]);
  if (!vtkCBC3DLabelValues::ToCodes(labels, out.Codes, d, out.StoredLower, out.StoredSize, out.Labels.data(), threads))
  {
    return false;
  }
  cbc3d::IndexLabelRuns(out, threads);
  return true;
}
} // namespace

namespace
{
// A rank's piece carries the whole image's tissue box (LatticeBox field data, structured
// indices); the core takes it in the piece's own indices.
bool ReadLatticeBox(vtkImageData* image, const int extent[6], cbc3d::LabelImage& out, std::string& error)
{
  vtkDataArray* box = image->GetFieldData()->GetArray(vtkCBC3DArrayNames::LatticeBox);
  if (!box)
  {
    return true;
  }
  if (box->GetNumberOfValues() != 6)
  {
    error = "the image's LatticeBox field array must hold 6 values (lower x y z, upper x y z)";
    return false;
  }
  const int components = box->GetNumberOfComponents();
  auto value = [&](int i) { return int(box->GetComponent(i / components, i % components)); };
  for (int a = 0; a < 3; ++a)
  {
    out.LatticeBoxLower[a] = value(a) - extent[2 * a];
    out.LatticeBoxUpper[a] = value(3 + a) - extent[2 * a];
  }
  out.HasLatticeBox = true;
  return true;
}
} // namespace

bool ToLabelImage(vtkImageData* image, vtkDataArray* labels,
  const std::vector<vtkTypeInt64>& backgroundLabels, cbc3d::LabelImage& out, std::string& error,
  std::vector<std::int64_t> otherValues, int threads)
{
  if (!image)
  {
    error = "no input image";
    return false;
  }
  if (!labels)
  {
    std::string names;
    vtkPointData* pointData = image->GetPointData();
    for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
    {
      const char* name = pointData->GetArrayName(a);
      names += std::string(names.empty() ? "" : ", ") + (name ? name : "(unnamed)");
    }
    error = "the input image has no label array (no active point scalars, or the chosen array "
            "is missing); its point arrays: " + (names.empty() ? std::string("none") : names);
    return false;
  }
  const std::string name = labels->GetName() ? labels->GetName() : "(unnamed)";
  if (labels->GetNumberOfComponents() != 1)
  {
    std::ostringstream msg;
    msg << "the label array '" << name << "' has " << labels->GetNumberOfComponents()
        << " components; a label map has one";
    error = msg.str();
    return false;
  }
  if (labels->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    error = "the label array '" + name + "' is not point data with one value per voxel";
    return false;
  }
  if (labels->GetDataType() == VTK_BIT)
  {
    error = "the label array '" + name + "' is a bit array; use an integer or float array";
    return false;
  }

  int dims[3];
  image->GetDimensions(dims);
  int extent[6];
  image->GetExtent(extent);
  out.Dimensions = { dims[0], dims[1], dims[2] };
  double origin[3];
  image->TransformContinuousIndexToPhysicalPoint(extent[0], extent[2], extent[4], origin);
  out.Origin = Eigen::Vector3d(origin[0], origin[1], origin[2]);
  const double* spacing = image->GetSpacing();
  out.Spacing = Eigen::Vector3d(spacing[0], spacing[1], spacing[2]);
  vtkMatrix3x3* direction = image->GetDirectionMatrix();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      out.Direction(r, c) = direction->GetElement(r, c);
    }
  }

  // One table for the image's labels, the background labels and the caller's (a mesh's), so
  // every background label has a code too; the box of the voxels that are not the first
  // background label comes from the same pass.
  std::array<int, 3> lower = { 0, 0, 0 }, upper = { -1, -1, -1 };
  const bool collected = backgroundLabels.empty()
    ? vtkCBC3DLabelValues::CollectValues(labels, otherValues, error, threads)
    : vtkCBC3DLabelValues::CollectImageValues(
        labels, out.Dimensions, backgroundLabels.front(), otherValues, error, lower, upper, threads);
  if (!collected)
  {
    return false;
  }
  otherValues.insert(otherValues.end(), backgroundLabels.begin(), backgroundLabels.end());
  out.Codes = cbc3d::LabelCodes::ForValues(std::move(otherValues));
  out.BackgroundLabels.assign(backgroundLabels.size(), 0);
  for (std::size_t b = 0; b < backgroundLabels.size(); ++b)
  {
    out.Codes.FindCode(backgroundLabels[b], out.BackgroundLabels[b]);
  }
  if (!StoreLabels(labels, lower, upper, out, threads))
  {
    error = "internal error: an image value found no label code";
    return false;
  }
  if (!ReadLatticeBox(image, extent, out, error))
  {
    return false;
  }
  const cbc3d::Status valid = cbc3d::ValidateLabelImage(out);
  if (!valid.IsOk())
  {
    error = valid.GetMessage();
    return false;
  }
  cbc3d::OrthonormalizeDirection(out);
  return true;
}

namespace
{
// A cell array's offsets for `count` tets, and its connectivity, in the array type Ids.
template <typename Ids>
vtkSmartPointer<Ids> TetOffsets(vtkIdType count)
{
  auto offsets = vtkSmartPointer<Ids>::New();
  offsets->SetNumberOfValues(count + 1);
  for (vtkIdType t = 0; t <= count; ++t)
    offsets->SetValue(t, static_cast<typename Ids::ValueType>(4 * t));
  return offsets;
}

template <typename Ids>
vtkSmartPointer<Ids> TetConnectivity(const std::vector<cbc3d::Tet>& tets)
{
  auto connectivity = vtkSmartPointer<Ids>::New();
  connectivity->SetNumberOfValues(4 * vtkIdType(tets.size()));
  auto* out = connectivity->GetPointer(0);
  for (const cbc3d::Tet& tet : tets)
    out = std::copy(tet.begin(), tet.end(), out);
  return connectivity;
}
} // namespace

void ToUnstructuredGrid(
  const cbc3d::TetMesh& mesh, const cbc3d::LabelCodes& codes, vtkUnstructuredGrid* out)
{
  const vtkIdType pointCount = static_cast<vtkIdType>(mesh.Points.size());
  const vtkIdType tetCount = static_cast<vtkIdType>(mesh.Tets.size());

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(pointCount);
  for (vtkIdType i = 0; i < pointCount; ++i)
  {
    points->SetPoint(i, mesh.Points[i].data());
  }

  // 32-bit connectivity where the offsets fit: half the bytes of vtkIdType's, in every stage's
  // output the pipeline holds.
  vtkNew<vtkCellArray> cells;
  if (4 * tetCount <= vtkIdType(std::numeric_limits<vtkTypeInt32>::max()))
    cells->SetData(TetOffsets<vtkTypeInt32Array>(tetCount), TetConnectivity<vtkTypeInt32Array>(mesh.Tets));
  else
    cells->SetData(TetOffsets<vtkTypeInt64Array>(tetCount), TetConnectivity<vtkTypeInt64Array>(mesh.Tets));
  out->Initialize();
  out->SetPoints(points);
  out->SetCells(VTK_TETRA, cells);
  out->GetCellData()->AddArray(
    vtkCBC3DLabelValues::FromCodes(mesh.Labels, codes, vtkCBC3DArrayNames::Label));
  out->GetCellData()->SetActiveScalars(vtkCBC3DArrayNames::Label);
}

void ToPolyData(const cbc3d::TaggedMesh& mesh, vtkPolyData* out)
{
  // Only the points the triangles use, renumbered in first-use order.
  std::vector<vtkIdType> newId(mesh.Points.size(), -1);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> triangles;
  std::vector<std::int32_t> sides;
  sides.reserve(2 * mesh.Triangles.size());
  vtkNew<vtkIntArray> surfaceIds;
  surfaceIds->SetName(vtkCBC3DArrayNames::SurfaceId);
  surfaceIds->SetNumberOfValues(static_cast<vtkIdType>(mesh.Triangles.size()));
  for (std::size_t s = 0; s < mesh.Surfaces.size(); ++s)
  {
    for (std::size_t t = mesh.SurfaceStart[s]; t < mesh.SurfaceStart[s + 1]; ++t)
    {
      vtkIdType ids[3];
      for (int k = 0; k < 3; ++k)
      {
        const cbc3d::PointId p = mesh.Triangles[t].Points[k];
        if (newId[p] < 0)
          newId[p] = points->InsertNextPoint(mesh.Points[p].data());
        ids[k] = newId[p];
      }
      triangles->InsertNextCell(3, ids);
      sides.insert(sides.end(), mesh.Triangles[t].Sides.begin(), mesh.Triangles[t].Sides.end());
      surfaceIds->SetValue(static_cast<vtkIdType>(t), mesh.Surfaces[s].Id);
    }
  }
  out->Initialize();
  out->SetPoints(points);
  out->SetPolys(triangles);
  out->GetCellData()->AddArray(
    vtkCBC3DLabelValues::FromCodes(sides, mesh.Codes, vtkCBC3DArrayNames::BoundaryLabels, 2));
  out->GetCellData()->AddArray(surfaceIds);
}

vtkDataArray* MeshLabels(vtkUnstructuredGrid* grid, std::string& error)
{
  vtkDataArray* labels = grid ? grid->GetCellData()->GetArray(vtkCBC3DArrayNames::Label) : nullptr;
  if (!grid)
  {
    error = "no input mesh";
  }
  else if (!labels || labels->GetNumberOfComponents() != 1 ||
    labels->GetNumberOfTuples() != grid->GetNumberOfCells())
  {
    error = "the mesh has no one-component 'Label' cell array";
    labels = nullptr;
  }
  return labels;
}

bool ToTissueCodes(const std::map<long long, double>& byValue, const cbc3d::LabelImage& image,
  std::map<std::int32_t, double>& byCode, std::string& error)
{
  byCode.clear();
  for (const auto& [value, setting] : byValue)
  {
    std::int32_t code = 0;
    if (!image.Codes.FindCode(value, code))
    {
      error = "the image has no label " + std::to_string(value);
      return false;
    }
    if (!image.IsTissue(code))
    {
      error = "label " + std::to_string(value) + " is background, not a tissue";
      return false;
    }
    byCode[code] = setting;
  }
  return true;
}

bool MeshLabelValues(vtkUnstructuredGrid* grid, std::vector<std::int64_t>& values, std::string& error)
{
  vtkDataArray* labels = MeshLabels(grid, error);
  return labels && vtkCBC3DLabelValues::CollectValues(labels, values, error);
}

namespace
{
// The points' coordinates, read straight from a double array where they are one (the
// stages' own output), else point by point.
void CopyPoints(vtkUnstructuredGrid* grid, std::vector<Eigen::Vector3d>& points)
{
  vtkDoubleArray* doubles = grid->GetPoints() ? vtkDoubleArray::SafeDownCast(grid->GetPoints()->GetData()) : nullptr;
  const vtkIdType count = static_cast<vtkIdType>(points.size());
  if (doubles)
    std::copy_n(doubles->GetPointer(0), 3 * count, points.data()->data());
  else
    for (vtkIdType i = 0; i < count; ++i)
      grid->GetPoint(i, points[i].data());
}

// The first cell that is not a tetrahedron of 4 points; -1 if none.
vtkIdType FirstCellNotTet(vtkUnstructuredGrid* grid)
{
  vtkUnsignedCharArray* types = grid->GetCellTypesArray();
  vtkCellArray* cells = grid->GetCells();
  const vtkIdType count = grid->GetNumberOfCells();
  for (vtkIdType c = 0; c < count; ++c)
  {
    if ((types ? types->GetValue(c) : grid->GetCellType(c)) != VTK_TETRA || cells->GetCellSize(c) != 4)
      return c;
  }
  return -1;
}

// Each tet's four point ids, straight from the cell array's storage (32 or 64 bits).
void CopyTets(vtkCellArray* cells, std::vector<cbc3d::Tet>& tets)
{
  if (tets.empty())
    return;
  auto copy = [&tets](auto* offsets, auto* connectivity) {
    const auto* offset = offsets->GetPointer(0);
    const auto* ids = connectivity->GetPointer(0);
    for (std::size_t c = 0; c < tets.size(); ++c)
      for (int v = 0; v < 4; ++v)
        tets[c][v] = static_cast<cbc3d::PointId>(ids[offset[c] + v]);
  };
  if (cells->IsStorage64Bit())
    copy(cells->GetOffsetsArray64(), cells->GetConnectivityArray64());
  else
    copy(cells->GetOffsetsArray32(), cells->GetConnectivityArray32());
}
} // namespace

bool FromUnstructuredGrid(vtkUnstructuredGrid* grid, cbc3d::TetMesh& out, std::string& error,
  const cbc3d::LabelCodes& codes)
{
  out = cbc3d::TetMesh();
  vtkDataArray* labels = MeshLabels(grid, error);
  if (!labels)
  {
    return false;
  }
  if (grid->GetNumberOfPoints() > vtkIdType(cbc3d::MaxPoints))
  {
    error = "the mesh has more than 2^31 - 1 points: mesh it in pieces (over MPI ranks)";
    return false;
  }
  out.Points.resize(grid->GetNumberOfPoints());
  CopyPoints(grid, out.Points);
  const vtkIdType cellCount = grid->GetNumberOfCells();
  const vtkIdType notTet = FirstCellNotTet(grid);
  if (notTet >= 0)
  {
    error = "the mesh has a cell that is not a tetrahedron (cell " + std::to_string(notTet) + ")";
    return false;
  }
  out.Tets.resize(cellCount);
  out.Labels.resize(cellCount);
  CopyTets(grid->GetCells(), out.Tets);
  if (!vtkCBC3DLabelValues::ToCodes(labels, codes, out.Labels.data()))
  {
    error = "the mesh's 'Label' array holds a label that is not a 32-bit integer, or not an integer";
    return false;
  }
  return true;
}

bool ToTaggedMesh(vtkUnstructuredGrid* grid, vtkTypeInt64 outside, cbc3d::TaggedMesh& out, std::string& error)
{
  std::vector<std::int64_t> values{ outside };
  if (!MeshLabelValues(grid, values, error))
  {
    return false;
  }
  const cbc3d::LabelCodes codes = cbc3d::LabelCodes::ForValues(std::move(values));
  cbc3d::TetMesh tets;
  std::int32_t outsideCode = 0;
  if (!FromUnstructuredGrid(grid, tets, error, codes) || !codes.FindCode(outside, outsideCode))
  {
    return false;
  }
  const cbc3d::Status status = cbc3d::BuildTaggedMesh(tets, outsideCode, out, codes);
  error = status.GetMessage();
  return status.IsOk();
}

cbc3d::Progress MakeProgress(vtkAlgorithm* algorithm)
{
  return [algorithm](double fraction) {
    algorithm->UpdateProgress(fraction);
    return !algorithm->CheckAbort();
  };
}
} // namespace vtkCBC3DConvert
