#include "vtkCBC3DConvert.h"

#include "vtkCBC3DArrayNames.h"

#include <vtkAlgorithm.h>
#include <vtkArrayDispatch.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArrayRange.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

namespace
{
// Copies any real-valued array into int32 labels, refusing fractions and values out of range.
struct CopyLabels
{
  std::int32_t* Out = nullptr;
  std::string Error;

  template <typename ArrayT>
  void operator()(ArrayT* array)
  {
    constexpr double lowest = std::numeric_limits<std::int32_t>::min();
    constexpr double highest = std::numeric_limits<std::int32_t>::max();
    std::int64_t i = 0;
    for (const auto value : vtk::DataArrayValueRange<1>(array))
    {
      const double v = static_cast<double>(value);
      if (!(v >= lowest && v <= highest))
      {
        std::ostringstream msg;
        msg << "the label array holds " << v << ", which is not a 32-bit integer label";
        this->Error = msg.str();
        return;
      }
      if (v != std::floor(v))
      {
        std::ostringstream msg;
        msg << "the label array holds the non-integral value " << v
            << "; a label map needs whole-number labels";
        this->Error = msg.str();
        return;
      }
      this->Out[i++] = static_cast<std::int32_t>(v);
    }
  }
};
} // namespace

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

bool ToLabelImage(vtkImageData* image, vtkDataArray* labels,
  const std::vector<int>& backgroundLabels, cbc3d::LabelImage& out, std::string& error)
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
  out.BackgroundLabels.assign(backgroundLabels.begin(), backgroundLabels.end());

  out.Labels.resize(labels->GetNumberOfTuples());
  CopyLabels copy;
  copy.Out = out.Labels.data();
  if (!vtkArrayDispatch::Dispatch::Execute(labels, copy))
  {
    copy(labels); // arrays the dispatcher does not know, through the generic API
  }
  if (!copy.Error.empty())
  {
    error = copy.Error;
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

void ToUnstructuredGrid(const cbc3d::TetMesh& mesh, vtkUnstructuredGrid* out)
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

  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(tetCount + 1);
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(4 * tetCount);
  vtkNew<vtkIntArray> labels;
  labels->SetName(vtkCBC3DArrayNames::Label);
  labels->SetNumberOfValues(tetCount);
  for (vtkIdType t = 0; t < tetCount; ++t)
  {
    offsets->SetValue(t, 4 * t);
    for (int v = 0; v < 4; ++v)
    {
      connectivity->SetValue(4 * t + v, mesh.Tets[t][v]);
    }
    labels->SetValue(t, mesh.Labels[t]);
  }
  offsets->SetValue(tetCount, 4 * tetCount);

  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  out->Initialize();
  out->SetPoints(points);
  out->SetCells(VTK_TETRA, cells);
  out->GetCellData()->AddArray(labels);
  out->GetCellData()->SetActiveScalars(vtkCBC3DArrayNames::Label);
}

void ToPolyData(const cbc3d::TaggedMesh& mesh, vtkPolyData* out)
{
  // Only the points the triangles use, renumbered in first-use order.
  std::vector<vtkIdType> newId(mesh.Points.size(), -1);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> triangles;
  vtkNew<vtkIntArray> sides;
  sides->SetName(vtkCBC3DArrayNames::BoundaryLabels);
  sides->SetNumberOfComponents(2);
  sides->SetNumberOfTuples(static_cast<vtkIdType>(mesh.Triangles.size()));
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
      sides->SetTypedComponent(static_cast<vtkIdType>(t), 0, mesh.Triangles[t].Sides[0]);
      sides->SetTypedComponent(static_cast<vtkIdType>(t), 1, mesh.Triangles[t].Sides[1]);
      surfaceIds->SetValue(static_cast<vtkIdType>(t), mesh.Surfaces[s].Id);
    }
  }
  out->Initialize();
  out->SetPoints(points);
  out->SetPolys(triangles);
  out->GetCellData()->AddArray(sides);
  out->GetCellData()->AddArray(surfaceIds);
}

bool FromUnstructuredGrid(vtkUnstructuredGrid* grid, cbc3d::TetMesh& out, std::string& error)
{
  out = cbc3d::TetMesh();
  if (!grid)
  {
    error = "no input mesh";
    return false;
  }
  vtkDataArray* labels = grid->GetCellData()->GetArray(vtkCBC3DArrayNames::Label);
  const vtkIdType cellCount = grid->GetNumberOfCells();
  if (!labels || labels->GetNumberOfComponents() != 1 || labels->GetNumberOfTuples() != cellCount)
  {
    error = "the mesh has no one-component 'Label' cell array";
    return false;
  }
  out.Points.resize(grid->GetNumberOfPoints());
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    grid->GetPoint(i, out.Points[i].data());
  }
  out.Tets.resize(cellCount);
  out.Labels.resize(cellCount);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < cellCount; ++c)
  {
    if (grid->GetCellType(c) != VTK_TETRA)
    {
      error = "the mesh has a cell that is not a tetrahedron (cell " + std::to_string(c) + ")";
      return false;
    }
    grid->GetCellPoints(c, ids);
    for (int v = 0; v < 4; ++v)
    {
      out.Tets[c][v] = ids->GetId(v);
    }
    out.Labels[c] = static_cast<std::int32_t>(labels->GetTuple1(c));
  }
  return true;
}

bool ToTaggedMesh(vtkUnstructuredGrid* grid, std::int32_t outside, cbc3d::TaggedMesh& out, std::string& error)
{
  cbc3d::TetMesh tets;
  if (!FromUnstructuredGrid(grid, tets, error))
  {
    return false;
  }
  const cbc3d::Status status = cbc3d::BuildTaggedMesh(tets, outside, out);
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
