#include "vtkCBC3DSeamPoints.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DPieces.h"

#include "cbc3d/base/TetGeometry.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnstructuredGrid.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace
{
// The volume of the tet whose corners are the columns of `c`.
double TetVolume(const Eigen::Matrix<double, 3, 4>& c)
{
  return std::abs(cbc3d::SignedVolume(c.col(0), c.col(1), c.col(2), c.col(3)));
}
} // namespace

namespace vtkCBC3DSeamPoints
{
std::vector<std::int64_t> AxisKeys(vtkUnstructuredGrid* mesh, int axis)
{
  // (Read as integers: a packed key has more bits than a double holds.)
  auto* keys = vtkIdTypeArray::SafeDownCast(mesh->GetPointData()->GetArray(vtkCBC3DPieces::LatticeKeyName));
  std::vector<std::int64_t> along(mesh->GetNumberOfPoints(), 0);
  for (vtkIdType p = 0; keys && p < mesh->GetNumberOfPoints(); ++p)
    along[p] = vtkCBC3DPieces::UnpackKey(keys->GetValue(p))[axis];
  return along;
}

Seams FindSeams(vtkMultiProcessController* controller, vtkUnstructuredGrid* mesh, int axis,
  const std::vector<std::int64_t>& cutKeys, std::int64_t cubeKeys)
{
  vtkDataArray* ids = mesh->GetPointData()->GetArray(vtkCBC3DArrayNames::GlobalIds);
  const std::vector<std::int64_t> along = AxisKeys(mesh, axis);
  vtkNew<vtkTypeInt64Array> send, all;
  for (vtkIdType p = 0; ids && p < mesh->GetNumberOfPoints(); ++p)
  {
    const bool nearCut = std::any_of(cutKeys.begin(), cutKeys.end(),
      [&](std::int64_t cut) { return std::abs(along[p] - cut) <= cubeKeys; });
    if (nearCut)
    {
      send->InsertNextValue(static_cast<vtkTypeInt64>(ids->GetComponent(p, 0)));
    }
  }
  controller->AllGatherV(send, all);
  std::unordered_map<vtkIdType, int> holders; // ranks that name each point
  for (vtkIdType r = 0; r < all->GetNumberOfValues(); ++r)
    ++holders[vtkIdType(all->GetValue(r))];
  Seams seams;
  for (const auto& [id, count] : holders)
    if (count > 1)
      seams.Points.insert(id);
  return seams;
}

std::map<vtkTypeInt64, double> TissueBeyondSlab(vtkMultiProcessController* controller, vtkUnstructuredGrid* mesh,
  int axis, const std::vector<std::int64_t>& cutKeys)
{
  const int me = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  const std::vector<std::int64_t> along = AxisKeys(mesh, axis);
  vtkDataArray* labels = mesh->GetCellData()->GetArray(vtkCBC3DArrayNames::Label);
  // Per label: the volume below the lower cut and above the upper one.
  std::map<vtkTypeInt64, std::array<double, 2>> beyond;
  vtkNew<vtkIdList> corners;
  for (vtkIdType t = 0; labels && t < mesh->GetNumberOfCells(); ++t)
  {
    mesh->GetCellPoints(t, corners);
    Eigen::Matrix<double, 3, 4> x;
    std::array<double, 4> belowLower{}, aboveUpper{};
    for (int c = 0; c < 4; ++c)
    {
      mesh->GetPoint(corners->GetId(c), x.col(c).data());
      const std::int64_t key = along[corners->GetId(c)];
      belowLower[c] = me > 0 ? double(cutKeys[me - 1] - key) : -1.0;
      aboveUpper[c] = me + 1 < ranks ? double(key - cutKeys[me]) : -1.0;
    }
    const double volume = TetVolume(x);
    auto& sums = beyond[static_cast<vtkTypeInt64>(labels->GetComponent(t, 0))];
    sums[0] += volume * cbc3d::ShareAbove(belowLower);
    sums[1] += volume * cbc3d::ShareAbove(aboveUpper);
  }
  vtkNew<vtkDoubleArray> send, all;
  for (const auto& [label, sums] : beyond)
    for (const double value : { double(me), double(label), sums[0], sums[1] })
      send->InsertNextValue(value);
  controller->AllGatherV(send, all);
  std::map<vtkTypeInt64, double> offsets;
  for (vtkIdType r = 0; r + 3 < all->GetNumberOfValues(); r += 4)
  {
    const int rank = int(all->GetValue(r));
    const auto label = static_cast<vtkTypeInt64>(all->GetValue(r + 1));
    if (rank == me)
      offsets[label] += all->GetValue(r + 2) + all->GetValue(r + 3);
    else if (rank == me - 1)
      offsets[label] -= all->GetValue(r + 3); // the lower neighbour's tets above its upper cut
    else if (rank == me + 1)
      offsets[label] -= all->GetValue(r + 2);
  }
  return offsets;
}

std::map<vtkTypeInt64, double> TissueVolumes(vtkUnstructuredGrid* mesh)
{
  vtkDataArray* labels = mesh->GetCellData()->GetArray(vtkCBC3DArrayNames::Label);
  std::map<vtkTypeInt64, double> volumes;
  vtkNew<vtkIdList> corners;
  for (vtkIdType t = 0; labels && t < mesh->GetNumberOfCells(); ++t)
  {
    mesh->GetCellPoints(t, corners);
    Eigen::Matrix<double, 3, 4> x;
    for (int c = 0; c < 4; ++c)
      mesh->GetPoint(corners->GetId(c), x.col(c).data());
    volumes[static_cast<vtkTypeInt64>(labels->GetComponent(t, 0))] += TetVolume(x);
  }
  return volumes;
}
} // namespace vtkCBC3DSeamPoints
