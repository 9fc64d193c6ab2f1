#include "vtkCBC3DGatherPieces.h"

#include "vtkCBC3DArrayNames.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>

#include <vector>

namespace
{
// The pieces that hold tets.
std::vector<vtkUnstructuredGrid*> NonEmpty(const std::vector<vtkSmartPointer<vtkDataObject>>& pieces)
{
  std::vector<vtkUnstructuredGrid*> kept;
  for (const auto& piece : pieces)
  {
    auto* grid = vtkUnstructuredGrid::SafeDownCast(piece);
    if (grid && grid->GetNumberOfCells() > 0)
    {
      kept.push_back(grid);
    }
  }
  return kept;
}

// The points of all pieces at their global ids; false where a piece has none or an id is out of range.
bool PlacePoints(const std::vector<vtkUnstructuredGrid*>& pieces, vtkPoints* points, std::string& error)
{
  vtkIdType count = 0;
  for (vtkUnstructuredGrid* piece : pieces)
  {
    vtkDataArray* ids = piece->GetPointData()->GetArray(vtkCBC3DArrayNames::GlobalIds);
    if (!ids || ids->GetNumberOfTuples() != piece->GetNumberOfPoints())
    {
      error = "the ranks' pieces carry no GlobalIds point array to merge them by (mesh with CBC3D Image To Mesh under MPI)";
      return false;
    }
    for (vtkIdType p = 0; p < ids->GetNumberOfTuples(); ++p)
    {
      count = std::max(count, vtkIdType(ids->GetComponent(p, 0)) + 1);
    }
  }
  points->SetNumberOfPoints(count);
  std::vector<char> placed(count, 0);
  for (vtkUnstructuredGrid* piece : pieces)
  {
    vtkDataArray* ids = piece->GetPointData()->GetArray(vtkCBC3DArrayNames::GlobalIds);
    for (vtkIdType p = 0; p < ids->GetNumberOfTuples(); ++p)
    {
      const vtkIdType id = vtkIdType(ids->GetComponent(p, 0));
      if (id < 0)
      {
        error = "a piece holds a negative global point id";
        return false;
      }
      points->SetPoint(id, piece->GetPoint(p));
      placed[id] = 1;
    }
  }
  for (vtkIdType id = 0; id < count; ++id)
  {
    if (!placed[id])
    {
      error = "the ranks' global point ids leave gaps: the pieces are not one mesh";
      return false;
    }
  }
  return true;
}

// The tets of all pieces on the merged points, with every cell array the first piece has.
void AppendCells(const std::vector<vtkUnstructuredGrid*>& pieces, vtkUnstructuredGrid* whole)
{
  vtkNew<vtkCellArray> cells;
  std::vector<int> types;
  vtkCellData* out = whole->GetCellData();
  out->CopyAllocate(pieces.front()->GetCellData());
  vtkNew<vtkIdList> corners;
  for (vtkUnstructuredGrid* piece : pieces)
  {
    vtkDataArray* ids = piece->GetPointData()->GetArray(vtkCBC3DArrayNames::GlobalIds);
    for (vtkIdType c = 0; c < piece->GetNumberOfCells(); ++c)
    {
      piece->GetCellPoints(c, corners);
      for (vtkIdType k = 0; k < corners->GetNumberOfIds(); ++k)
      {
        corners->SetId(k, vtkIdType(ids->GetComponent(corners->GetId(k), 0)));
      }
      out->CopyData(piece->GetCellData(), c, cells->InsertNextCell(corners));
      types.push_back(piece->GetCellType(c));
    }
  }
  whole->SetCells(types.data(), cells);
}
} // namespace

namespace vtkCBC3DGatherPieces
{
void Gather(vtkMultiProcessController* controller, vtkUnstructuredGrid* piece,
  vtkSmartPointer<vtkUnstructuredGrid>& whole, std::string& error)
{
  vtkNew<vtkUnstructuredGrid> sent;
  if (piece)
  {
    sent->ShallowCopy(piece);
  }
  std::vector<vtkSmartPointer<vtkDataObject>> pieces;
  controller->Gather(sent, pieces, 0);
  if (controller->GetLocalProcessId() != 0)
  {
    return;
  }
  const std::vector<vtkUnstructuredGrid*> kept = NonEmpty(pieces);
  whole = vtkSmartPointer<vtkUnstructuredGrid>::New();
  if (kept.size() == 1)
  {
    whole->ShallowCopy(kept.front());
    return;
  }
  if (kept.empty())
  {
    error = "no rank holds a tet";
    whole = nullptr;
    return;
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble(); // the pieces' places, not rounded to single precision
  if (!PlacePoints(kept, points, error))
  {
    whole = nullptr;
    return;
  }
  whole->SetPoints(points);
  AppendCells(kept, whole);
  whole->GetFieldData()->ShallowCopy(kept.front()->GetFieldData());
}
} // namespace vtkCBC3DGatherPieces
