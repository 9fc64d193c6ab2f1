#include "vtkCBC3DBandTets.h"

#include "vtkCBC3DArrayNames.h"

#include "cbc3d/base/TetGeometry.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkMultiProcessController.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace vtkCBC3DBandTets
{
BandTets::BandTets()
  : Rows(vtkSmartPointer<vtkTypeInt64Array>::New())
  , Places(vtkSmartPointer<vtkDoubleArray>::New())
{
}

BandTets::~BandTets() = default;

vtkIdType BandTets::Count() const
{
  return this->Rows->GetNumberOfValues() / RowSize;
}

const vtkTypeInt64* BandTets::Row(vtkIdType r) const
{
  return this->Rows->GetPointer(RowSize * r);
}

const double* BandTets::PlacesOf(vtkIdType r) const
{
  return this->Places->GetPointer(12 * r);
}

void Share(vtkMultiProcessController* controller, vtkUnstructuredGrid* owned, const std::vector<std::int64_t>& axisKeys,
  const std::vector<std::int64_t>& cutKeys, std::int64_t cubeKeys, BandTets& all)
{
  const int me = controller->GetLocalProcessId();
  BandTets mine;
  vtkDataArray* ids = owned->GetPointData()->GetArray(vtkCBC3DArrayNames::GlobalIds);
  vtkDataArray* labels = owned->GetCellData()->GetArray(vtkCBC3DArrayNames::Label);
  auto nearCut = [&](vtkIdType p) {
    return std::any_of(cutKeys.begin(), cutKeys.end(),
      [&](std::int64_t cut) { return std::abs(axisKeys[p] - cut) <= ReachCubes * cubeKeys; });
  };
  vtkNew<vtkIdList> corners;
  for (vtkIdType t = 0; ids && labels && t < owned->GetNumberOfCells(); ++t)
  {
    owned->GetCellPoints(t, corners);
    if (std::none_of(corners->begin(), corners->end(), nearCut))
      continue;
    mine.Rows->InsertNextValue(me);
    for (const vtkIdType p : *corners)
    {
      mine.Rows->InsertNextValue(static_cast<vtkTypeInt64>(ids->GetComponent(p, 0)));
      double x[3];
      owned->GetPoint(p, x);
      for (const double value : x)
        mine.Places->InsertNextValue(value);
    }
    mine.Rows->InsertNextValue(static_cast<vtkTypeInt64>(labels->GetComponent(t, 0)));
    for (const vtkIdType p : *corners)
      mine.Rows->InsertNextValue(axisKeys[p]);
  }
  controller->AllGatherV(mine.Rows, all.Rows);
  controller->AllGatherV(mine.Places, all.Places);
}

RunMesh::RunMesh(vtkDataArray* labelType)
  : Points(vtkSmartPointer<vtkPoints>::New())
  , Labels(vtkSmartPointer<vtkDataArray>::Take(labelType->NewInstance()))
{
  this->Points->SetDataTypeToDouble();
  this->Labels->SetName(vtkCBC3DArrayNames::Label);
}

RunMesh::~RunMesh() = default;

vtkIdType RunMesh::AddPoint(vtkIdType id, std::int64_t key, const double x[3])
{
  const auto [entry, added] = this->Local.emplace(id, this->Points->GetNumberOfPoints());
  if (added)
  {
    this->Points->InsertNextPoint(x);
    this->Keys.push_back(key);
  }
  return entry->second;
}

double RunMesh::Add(const vtkTypeInt64 ids[4], const vtkTypeInt64 keys[4], const double* places, double label)
{
  std::array<vtkIdType, 4> corners;
  for (int c = 0; c < 4; ++c)
    corners[c] = this->AddPoint(vtkIdType(ids[c]), keys[c], places + 3 * c);
  this->Corners.push_back(corners);
  this->Labels->InsertNextTuple1(label);
  auto corner = [places](int c) { return Eigen::Vector3d(places[3 * c], places[3 * c + 1], places[3 * c + 2]); };
  return std::abs(cbc3d::SignedVolume(corner(0), corner(1), corner(2), corner(3)));
}

void RunMesh::AddOwned(vtkUnstructuredGrid* owned, const std::vector<std::int64_t>& axisKeys,
  const std::function<bool(std::int64_t)>& keep)
{
  vtkDataArray* ids = owned->GetPointData()->GetArray(vtkCBC3DArrayNames::GlobalIds);
  vtkDataArray* labels = owned->GetCellData()->GetArray(vtkCBC3DArrayNames::Label);
  vtkNew<vtkIdList> corners;
  for (vtkIdType t = 0; t < owned->GetNumberOfCells(); ++t)
  {
    owned->GetCellPoints(t, corners);
    if (std::none_of(corners->begin(), corners->end(), [&](vtkIdType p) { return keep(axisKeys[p]); }))
      continue;
    vtkTypeInt64 tet[4], keys[4];
    double places[12];
    for (int c = 0; c < 4; ++c)
    {
      tet[c] = static_cast<vtkTypeInt64>(ids->GetComponent(corners->GetId(c), 0));
      keys[c] = axisKeys[corners->GetId(c)];
      owned->GetPoint(corners->GetId(c), places + 3 * c);
    }
    this->Add(tet, keys, places, labels->GetComponent(t, 0));
  }
}

std::map<vtkTypeInt64, double> RunMesh::AddOthers(
  const BandTets& all, int me, const std::function<bool(std::int64_t)>& keep)
{
  std::map<vtkTypeInt64, double> volumes;
  for (vtkIdType r = 0; r < all.Count(); ++r)
  {
    const vtkTypeInt64* row = all.Row(r);
    if (row[0] != me && std::any_of(row + 6, row + 10, keep))
      volumes[row[5]] += this->Add(row + 1, row + 6, all.PlacesOf(r), double(row[5]));
  }
  return volumes;
}

vtkSmartPointer<vtkUnstructuredGrid> RunMesh::Make(const std::vector<vtkIdType>& free)
{
  vtkNew<vtkUnsignedCharArray> fixed;
  fixed->SetName(vtkCBC3DArrayNames::FixedPoints);
  fixed->SetNumberOfValues(this->Points->GetNumberOfPoints());
  fixed->Fill(1);
  for (const vtkIdType p : free)
    fixed->SetValue(p, 0);
  vtkNew<vtkCellArray> tets;
  for (const auto& corners : this->Corners)
    tets->InsertNextCell(4, corners.data());
  auto mesh = vtkSmartPointer<vtkUnstructuredGrid>::New();
  mesh->SetPoints(this->Points);
  mesh->SetCells(VTK_TETRA, tets);
  mesh->GetCellData()->AddArray(this->Labels);
  mesh->GetPointData()->AddArray(fixed);
  return mesh;
}
} // namespace vtkCBC3DBandTets
