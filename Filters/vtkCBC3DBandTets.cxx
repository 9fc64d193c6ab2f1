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
#include <unordered_map>
#include <vector>

namespace
{
// The tets bound for one rank, each corner once.
struct Outgoing
{
  std::unordered_map<vtkIdType, vtkTypeInt64> Index;
  std::vector<vtkTypeInt64> Ids, Keys, Corners, Labels;
  std::vector<double> Places;

  void Add(vtkUnstructuredGrid* owned, vtkDataArray* ids, const std::vector<std::int64_t>& axisKeys,
    vtkIdList* corners, vtkTypeInt64 label)
  {
    for (const vtkIdType p : *corners)
    {
      const auto [entry, added] = this->Index.emplace(p, vtkTypeInt64(this->Ids.size()));
      if (added)
      {
        this->Ids.push_back(static_cast<vtkTypeInt64>(ids->GetComponent(p, 0)));
        this->Keys.push_back(axisKeys[p]);
        double x[3];
        owned->GetPoint(p, x);
        this->Places.insert(this->Places.end(), x, x + 3);
      }
      this->Corners.push_back(entry->second);
    }
    this->Labels.push_back(label);
  }

  // In BandTets' layout, as one sender's part.
  void Pack(vtkTypeInt64Array* numbers, vtkDoubleArray* places) const
  {
    numbers->SetNumberOfValues(vtkIdType(2 + 2 * this->Ids.size() + this->Corners.size() + this->Labels.size()));
    vtkTypeInt64* out = numbers->GetPointer(0);
    *out++ = vtkTypeInt64(this->Ids.size());
    *out++ = vtkTypeInt64(this->Labels.size());
    for (const auto* part : { &this->Ids, &this->Keys, &this->Corners, &this->Labels })
      out = std::copy(part->begin(), part->end(), out);
    places->SetNumberOfValues(vtkIdType(this->Places.size()));
    std::copy(this->Places.begin(), this->Places.end(), places->GetPointer(0));
  }
};
} // namespace

namespace vtkCBC3DBandTets
{
BandTets::BandTets()
  : Numbers(vtkSmartPointer<vtkTypeInt64Array>::New())
  , Places(vtkSmartPointer<vtkDoubleArray>::New())
{
}

BandTets::~BandTets() = default;

void Share(vtkMultiProcessController* controller, vtkUnstructuredGrid* owned, const std::vector<std::int64_t>& axisKeys,
  const std::vector<std::int64_t>& cutKeys, std::int64_t cubeKeys, BandTets& received)
{
  const int me = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  std::vector<Outgoing> outgoing(ranks);
  vtkDataArray* ids = owned->GetPointData()->GetArray(vtkCBC3DArrayNames::GlobalIds);
  vtkDataArray* labels = owned->GetCellData()->GetArray(vtkCBC3DArrayNames::Label);
  vtkNew<vtkIdList> corners;
  std::vector<int> bound;
  for (vtkIdType t = 0; ids && labels && t < owned->GetNumberOfCells(); ++t)
  {
    owned->GetCellPoints(t, corners);
    // The ranks beside each cut near a corner.
    bound.clear();
    for (std::size_t c = 0; c < cutKeys.size(); ++c)
      if (std::any_of(corners->begin(), corners->end(),
            [&](vtkIdType p) { return std::abs(axisKeys[p] - cutKeys[c]) <= ReachCubes * cubeKeys; }))
        for (const int rank : { int(c), int(c) + 1 })
          if (rank != me && rank < ranks && std::find(bound.begin(), bound.end(), rank) == bound.end())
            bound.push_back(rank);
    for (const int rank : bound)
      outgoing[rank].Add(owned, ids, axisKeys, corners, static_cast<vtkTypeInt64>(labels->GetComponent(t, 0)));
  }
  for (int rank = 0; rank < ranks; ++rank)
  {
    vtkNew<vtkTypeInt64Array> numbers, numbersHere;
    vtkNew<vtkDoubleArray> places, placesHere;
    if (rank != me)
      outgoing[rank].Pack(numbers, places);
    outgoing[rank] = Outgoing();
    controller->GatherV(numbers, numbersHere, rank);
    controller->GatherV(places, placesHere, rank);
    if (rank == me)
    {
      received.Numbers = numbersHere;
      received.Places = placesHere;
    }
  }
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
  const BandTets& received, const std::function<bool(std::int64_t)>& keep)
{
  std::map<vtkTypeInt64, double> volumes;
  const vtkIdType size = received.Numbers->GetNumberOfValues();
  for (vtkIdType at = 0, placesAt = 0; at < size;)
  {
    const vtkTypeInt64* numbers = received.Numbers->GetPointer(at);
    const vtkTypeInt64 points = numbers[0], tets = numbers[1];
    const vtkTypeInt64* ids = numbers + 2;
    const vtkTypeInt64* keys = ids + points;
    const vtkTypeInt64* corners = keys + points;
    const vtkTypeInt64* labels = corners + 4 * tets;
    const double* places = received.Places->GetPointer(placesAt);
    for (vtkTypeInt64 t = 0; t < tets; ++t)
    {
      vtkTypeInt64 tet[4], tetKeys[4];
      double tetPlaces[12];
      for (int c = 0; c < 4; ++c)
      {
        const vtkTypeInt64 p = corners[4 * t + c];
        tet[c] = ids[p];
        tetKeys[c] = keys[p];
        std::copy(places + 3 * p, places + 3 * p + 3, tetPlaces + 3 * c);
      }
      if (std::any_of(tetKeys, tetKeys + 4, keep))
        volumes[labels[t]] += this->Add(tet, tetKeys, tetPlaces, double(labels[t]));
    }
    at += 2 + 2 * points + 5 * tets;
    placesAt += 3 * points;
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
  // Sized exactly, in 32 bits where the places fit, and the corners handed over: the run that
  // follows builds its own copies beside this mesh.
  vtkNew<vtkCellArray> tets;
  if (this->Points->GetNumberOfPoints() <= VTK_INT_MAX && 4 * this->Corners.size() < std::size_t(VTK_INT_MAX))
    tets->Use32BitStorage();
  tets->AllocateExact(vtkIdType(this->Corners.size()), 4 * vtkIdType(this->Corners.size()));
  for (const auto& corners : this->Corners)
    tets->InsertNextCell(4, corners.data());
  std::vector<std::array<vtkIdType, 4>>().swap(this->Corners);
  this->Labels->Squeeze();
  auto mesh = vtkSmartPointer<vtkUnstructuredGrid>::New();
  mesh->SetPoints(this->Points);
  mesh->SetCells(VTK_TETRA, tets);
  mesh->GetCellData()->AddArray(this->Labels);
  mesh->GetPointData()->AddArray(fixed);
  return mesh;
}
} // namespace vtkCBC3DBandTets
