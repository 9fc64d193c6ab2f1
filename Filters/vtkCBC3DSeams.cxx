#include "vtkCBC3DSeams.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DPieces.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <array>
#include <map>
#include <sstream>
#include <unordered_map>

namespace
{
using Face = std::array<vtkIdType, 3>; // global ids, ascending

// The rank whose slab holds `key` (4 times a tet's centre, or a point) by the borders' keys,
// times the same factor.
int OwnerOf(std::int64_t key, const std::vector<std::int64_t>& cutKeys, std::int64_t scale)
{
  int owner = 0;
  for (const std::int64_t cut : cutKeys)
    owner += key >= scale * cut;
  return owner;
}

struct LocalSeams
{
  std::vector<int> TetOwner;
  std::vector<int> PointOwner;
  std::vector<char> UsedByOthers; // by a tet another rank owns
};

LocalSeams FindOwners(vtkUnstructuredGrid* mesh, vtkIdTypeArray* ids, int axis,
  const std::vector<std::int64_t>& cutKeys)
{
  LocalSeams seams;
  const vtkIdType points = mesh->GetNumberOfPoints();
  seams.PointOwner.resize(points);
  for (vtkIdType p = 0; p < points; ++p)
    seams.PointOwner[p] = OwnerOf(vtkCBC3DPieces::UnpackKey(ids->GetValue(p))[axis], cutKeys, 1);
  seams.TetOwner.resize(mesh->GetNumberOfCells());
  seams.UsedByOthers.assign(points, 0);
  return seams;
}

// Numbers the points this rank owns (those its slab holds that some tet here uses) after the
// points of the ranks before it: global ids 0, 1, ... over the whole mesh.
std::vector<vtkIdType> NumberOwnPoints(vtkMultiProcessController* controller, const LocalSeams& seams,
  const std::vector<char>& usedByMine)
{
  const int me = controller->GetLocalProcessId();
  std::vector<vtkIdType> number(seams.PointOwner.size(), -1);
  long long mine = 0;
  for (std::size_t p = 0; p < number.size(); ++p)
    if (seams.PointOwner[p] == me && (usedByMine[p] || seams.UsedByOthers[p]))
      number[p] = vtkIdType(mine++);
  std::vector<long long> counts(controller->GetNumberOfProcesses(), 0);
  controller->AllGather(&mine, counts.data(), 1);
  long long before = 0;
  for (int r = 0; r < me; ++r)
    before += counts[r];
  for (vtkIdType& id : number)
    if (id >= 0)
      id += vtkIdType(before);
  return number;
}

// Sends the number and position of each point this rank owns and others use; gives the points
// its tets use and others own the numbers and positions their owners sent. Returns the points
// no owner sent.
long long ShareBorderPoints(vtkMultiProcessController* controller, vtkUnstructuredGrid* mesh,
  vtkIdTypeArray* keys, const LocalSeams& seams, const std::vector<char>& usedByMine,
  std::vector<vtkIdType>& number, long long& shared)
{
  const int me = controller->GetLocalProcessId();
  vtkNew<vtkTypeInt64Array> sendKeys, allKeys, sendNumbers, allNumbers;
  vtkNew<vtkDoubleArray> sendPositions, allPositions;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    if (seams.PointOwner[p] == me && seams.UsedByOthers[p])
    {
      sendKeys->InsertNextValue(keys->GetValue(p));
      sendNumbers->InsertNextValue(number[p]);
      double x[3];
      mesh->GetPoint(p, x);
      for (const double value : x)
        sendPositions->InsertNextValue(value);
    }
  }
  controller->AllGatherV(sendKeys, allKeys);
  controller->AllGatherV(sendNumbers, allNumbers);
  controller->AllGatherV(sendPositions, allPositions);
  shared = allKeys->GetNumberOfValues();
  std::unordered_map<vtkIdType, vtkIdType> sent;
  sent.reserve(allKeys->GetNumberOfValues());
  for (vtkIdType s = 0; s < allKeys->GetNumberOfValues(); ++s)
    sent.emplace(vtkIdType(allKeys->GetValue(s)), s);
  long long missing = 0;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    if (!usedByMine[p] || seams.PointOwner[p] == me)
      continue;
    const auto found = sent.find(keys->GetValue(p));
    if (found == sent.end())
    {
      ++missing;
      continue;
    }
    number[p] = vtkIdType(allNumbers->GetValue(found->second));
    mesh->GetPoints()->SetPoint(p, allPositions->GetPointer(3 * found->second));
  }
  return missing;
}

// The faces between a tet of this rank and a tet of another, with that rank, as rows of five
// numbers: this rank, the other, and the face's three global ids.
std::vector<long long> BorderFaces(vtkUnstructuredGrid* mesh, vtkIdTypeArray* ids, const LocalSeams& seams,
  const std::vector<char>& nearBorder, int me)
{
  std::map<Face, std::vector<int>> owners;
  vtkNew<vtkIdList> corners;
  for (vtkIdType t = 0; t < mesh->GetNumberOfCells(); ++t)
  {
    if (!nearBorder[t])
      continue;
    mesh->GetCellPoints(t, corners);
    for (int skip = 0; skip < 4; ++skip)
    {
      Face face;
      for (int c = 0, f = 0; c < 4; ++c)
        if (c != skip)
          face[f++] = ids->GetValue(corners->GetId(c));
      std::sort(face.begin(), face.end());
      owners[face].push_back(seams.TetOwner[t]);
    }
  }
  std::vector<long long> rows;
  for (const auto& [face, tetOwners] : owners)
  {
    if (tetOwners.size() != 2 || tetOwners[0] == tetOwners[1])
      continue;
    if (tetOwners[0] != me && tetOwners[1] != me)
      continue;
    const int other = tetOwners[0] == me ? tetOwners[1] : tetOwners[0];
    rows.insert(rows.end(), { me, other, face[0], face[1], face[2] });
  }
  return rows;
}

// Faces this rank lists on its border with another rank that the other does not, and the reverse.
long long UnmatchedFaces(vtkMultiProcessController* controller, const std::vector<long long>& mine,
  long long& total)
{
  vtkNew<vtkTypeInt64Array> send, all;
  for (const long long value : mine)
    send->InsertNextValue(value);
  controller->AllGatherV(send, all);
  const int me = controller->GetLocalProcessId();
  std::map<std::array<long long, 5>, int> seen; // (lower rank, higher rank, face) -> ranks that list it
  for (vtkIdType r = 0; r + 4 < all->GetNumberOfValues(); r += 5)
  {
    const long long a = all->GetValue(r), b = all->GetValue(r + 1);
    if (a != me && b != me)
      continue;
    seen[{ std::min(a, b), std::max(a, b), all->GetValue(r + 2), all->GetValue(r + 3), all->GetValue(r + 4) }]++;
  }
  total = all->GetNumberOfValues() / 5;
  long long unmatched = 0;
  for (const auto& entry : seen)
    unmatched += entry.second != 2;
  return unmatched;
}

// The tets this rank owns, their points compacted, every array kept (GlobalIds included).
void CopyOwned(vtkUnstructuredGrid* mesh, const LocalSeams& seams, const std::vector<vtkIdType>& number, int me,
  vtkUnstructuredGrid* owned)
{
  std::vector<vtkIdType> newId(mesh->GetNumberOfPoints(), -1);
  vtkNew<vtkPoints> points;
  if (mesh->GetPoints())
    points->SetDataType(mesh->GetPoints()->GetDataType());
  vtkPointData* inPoints = mesh->GetPointData();
  vtkPointData* outPoints = owned->GetPointData();
  outPoints->CopyAllocate(inPoints);
  vtkCellData* outCells = owned->GetCellData();
  outCells->CopyAllocate(mesh->GetCellData());
  vtkNew<vtkCellArray> tets;
  vtkNew<vtkIdList> corners;
  std::vector<int> types;
  for (vtkIdType t = 0; t < mesh->GetNumberOfCells(); ++t)
  {
    if (seams.TetOwner[t] != me)
      continue;
    mesh->GetCellPoints(t, corners);
    for (vtkIdType c = 0; c < corners->GetNumberOfIds(); ++c)
    {
      vtkIdType& id = newId[corners->GetId(c)];
      if (id < 0)
      {
        id = points->InsertNextPoint(mesh->GetPoint(corners->GetId(c)));
        outPoints->CopyData(inPoints, corners->GetId(c), id);
      }
      corners->SetId(c, id);
    }
    outCells->CopyData(mesh->GetCellData(), t, tets->InsertNextCell(corners));
    types.push_back(mesh->GetCellType(t));
  }
  vtkNew<vtkIdTypeArray> globalIds;
  globalIds->SetName(vtkCBC3DArrayNames::GlobalIds);
  globalIds->SetNumberOfValues(points->GetNumberOfPoints());
  for (std::size_t p = 0; p < newId.size(); ++p)
    if (newId[p] >= 0)
      globalIds->SetValue(newId[p], number[p]);
  outPoints->SetGlobalIds(globalIds);
  owned->SetPoints(points);
  owned->SetCells(types.data(), tets);
  owned->GetFieldData()->ShallowCopy(mesh->GetFieldData());
}
} // namespace

namespace vtkCBC3DSeams
{
bool KeepOwnedTets(vtkMultiProcessController* controller, int axis, const std::vector<std::int64_t>& cutKeys,
  vtkUnstructuredGrid* mesh, vtkUnstructuredGrid* owned, SeamReport& report, std::string& error)
{
  const int me = controller->GetLocalProcessId();
  auto* ids = vtkIdTypeArray::SafeDownCast(mesh->GetPointData()->GetArray(vtkCBC3DPieces::LatticeKeyName));
  if (!ids && mesh->GetNumberOfPoints() > 0)
  {
    error = "internal error: the piece's mesh has no lattice keys";
    return vtkCBC3DPieces::AllAgree(controller, false);
  }
  LocalSeams seams = FindOwners(mesh, ids, axis, cutKeys);
  std::vector<char> usedByMine(mesh->GetNumberOfPoints(), 0);
  vtkNew<vtkIdList> corners;
  for (vtkIdType t = 0; t < mesh->GetNumberOfCells(); ++t)
  {
    mesh->GetCellPoints(t, corners);
    std::int64_t sum = 0;
    for (vtkIdType c = 0; c < corners->GetNumberOfIds(); ++c)
      sum += vtkCBC3DPieces::UnpackKey(ids->GetValue(corners->GetId(c)))[axis];
    seams.TetOwner[t] = OwnerOf(sum, cutKeys, corners->GetNumberOfIds());
    std::vector<char>& used = seams.TetOwner[t] == me ? usedByMine : seams.UsedByOthers;
    for (vtkIdType c = 0; c < corners->GetNumberOfIds(); ++c)
      used[corners->GetId(c)] = 1;
  }
  // The tets whose faces may lie on a border: others' tets, and mine that touch them.
  std::vector<char> nearBorder(mesh->GetNumberOfCells(), 0);
  for (vtkIdType t = 0; t < mesh->GetNumberOfCells(); ++t)
  {
    mesh->GetCellPoints(t, corners);
    nearBorder[t] = seams.TetOwner[t] != me ||
      std::any_of(corners->begin(), corners->end(), [&](vtkIdType p) { return seams.UsedByOthers[p] != 0; });
  }
  const std::vector<long long> faces = BorderFaces(mesh, ids, seams, nearBorder, me);
  long long counts[4] = { 0, 0, 0, 0 }, sums[4];
  std::vector<vtkIdType> number = NumberOwnPoints(controller, seams, usedByMine);
  counts[2] = ShareBorderPoints(controller, mesh, ids, seams, usedByMine, number, counts[0]);
  counts[3] = UnmatchedFaces(controller, faces, counts[1]);
  controller->AllReduce(counts + 2, sums + 2, 2, vtkCommunicator::SUM_OP);
  report = { counts[0], counts[1] / 2, sums[2], sums[3] };
  if (report.MissingPoints > 0 || report.UnmatchedFaces > 0)
  {
    std::ostringstream message;
    message << "the ranks' pieces do not fit at their borders (" << report.UnmatchedFaces
            << " border faces and " << report.MissingPoints << " border points that only one rank has)";
    error = message.str();
    return false;
  }
  CopyOwned(mesh, seams, number, me, owned);
  return true;
}
} // namespace vtkCBC3DSeams
