#include "vtkCBC3DRankDeformation.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DBandTets.h"
#include "vtkCBC3DPieces.h"
#include "vtkCBC3DSeamPoints.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace
{
using vtkCBC3DBandTets::BandCubes;
using vtkCBC3DBandTets::ReachCubes;
using vtkCBC3DBandTets::BandTets;
using vtkCBC3DBandTets::RunMesh;
using vtkCBC3DSeamPoints::Seams;

// The slices past the reach of a rank's tets beyond its cuts that its own run sees: the
// boundary voxels just beyond whose nearest vertices it moves.
constexpr int SeamSlices = 2;

vtkIdType GlobalId(vtkDataArray* ids, vtkIdType p)
{
  return static_cast<vtkIdType>(ids->GetComponent(p, 0));
}

// Per label, the volume of its voxels in the slices [first, last] of the piece image (mm^3).
std::map<vtkTypeInt64, double> VoxelVolumes(vtkImageData* image, vtkDataArray* labels, int axis, int first, int last)
{
  std::map<vtkTypeInt64, double> volumes;
  int extent[6];
  image->GetExtent(extent);
  extent[2 * axis] = std::max(extent[2 * axis], first);
  extent[2 * axis + 1] = std::min(extent[2 * axis + 1], last);
  const double* spacing = image->GetSpacing();
  const double voxel = spacing[0] * spacing[1] * spacing[2];
  int ijk[3];
  for (ijk[2] = extent[4]; labels && ijk[2] <= extent[5]; ++ijk[2])
    for (ijk[1] = extent[2]; ijk[1] <= extent[3]; ++ijk[1])
      for (ijk[0] = extent[0]; ijk[0] <= extent[1]; ++ijk[0])
        volumes[static_cast<vtkTypeInt64>(labels->GetComponent(image->ComputePointId(ijk), 0))] += voxel;
  return volumes;
}

// Tells a run which boundary voxels it answers for: slices `first` to `last` of the image.
void SetWindow(vtkUnstructuredGrid* mesh, vtkImageData* image, int axis, int first, int last)
{
  std::array<double, 5> window;
  for (int a = 0; a < 3; ++a)
    window[a] = image->GetDirectionMatrix()->GetElement(a, axis);
  const double* origin = image->GetOrigin();
  const double at = window[0] * origin[0] + window[1] * origin[1] + window[2] * origin[2];
  window[3] = at + image->GetSpacing()[axis] * (first - 0.5);
  window[4] = at + image->GetSpacing()[axis] * (last + 0.5);
  vtkNew<vtkDoubleArray> array;
  array->SetName(vtkCBC3DArrayNames::VoxelWindow);
  array->SetNumberOfComponents(5);
  array->InsertNextTuple(window.data());
  mesh->GetFieldData()->AddArray(array);
}

// Tells a run what each tissue's volume should be: the piece image's voxels of it, offset.
void SetVolumeOffsets(vtkUnstructuredGrid* mesh, const std::map<vtkTypeInt64, double>& offsets)
{
  vtkNew<vtkDoubleArray> volumes;
  volumes->SetName(vtkCBC3DArrayNames::VolumeOffsets);
  volumes->SetNumberOfComponents(2);
  for (const auto& [label, offset] : offsets)
  {
    const double pair[2] = { double(label), offset };
    volumes->InsertNextTuple(pair);
  }
  mesh->GetFieldData()->AddArray(volumes);
}

// What both phases need: the layout, this rank, its piece and the run.
struct Phases
{
  const vtkCBC3DRankDeformation::Layout& Layout;
  int Me;
  int Ranks;
  vtkImageData* Image;
  vtkDataArray* ImageLabels;
  vtkUnstructuredGrid* Owned;
  std::vector<std::int64_t> AxisKeys;
  const vtkCBC3DRankDeformation::RunDeformation& Run;

  std::int64_t Band() const { return BandCubes * this->Layout.CubeKeys; }
  // So many lattice cubes in slices along the axis, rounded up.
  int Slices(int cubes) const
  {
    return int(std::ceil(cubes * this->Layout.Cube / this->Image->GetSpacing()[this->Layout.Axis]));
  }
  // The cuts of this rank's slab, in keys.
  std::vector<std::int64_t> OwnCuts() const
  {
    std::vector<std::int64_t> cuts;
    if (this->Me > 0)
      cuts.push_back(this->Layout.CutKeys[this->Me - 1]);
    if (this->Me + 1 < this->Ranks)
      cuts.push_back(this->Layout.CutKeys[this->Me]);
    return cuts;
  }
};

bool WithinBandOf(std::int64_t key, const std::vector<std::int64_t>& cuts, std::int64_t band)
{
  return std::any_of(cuts.begin(), cuts.end(), [&](std::int64_t cut) { return std::abs(key - cut) <= band; });
}

// The first phase: the rank's own tets, with its neighbours' tets near the cuts held about
// them, against its slab and the slices its tets and a little more reach past each cut, the
// seam points held. Each tissue aims at its slab's voxels, plus the tissue of its tets beyond
// the slab less its neighbours' inside it (`beyondSlab`), plus the neighbours' held tets.
std::string DeformOwnTets(const Phases& phases, const Seams& seams, const BandTets& received,
  const std::map<vtkTypeInt64, double>& beyondSlab)
{
  vtkUnstructuredGrid* owned = phases.Owned;
  vtkDataArray* ids = owned->GetPointData()->GetArray(vtkCBC3DArrayNames::GlobalIds);
  RunMesh mesh(owned->GetCellData()->GetArray(vtkCBC3DArrayNames::Label));
  mesh.AddOwned(owned, phases.AxisKeys, [](std::int64_t) { return true; });
  const std::vector<std::int64_t> cuts = phases.OwnCuts();
  std::map<vtkTypeInt64, double> offsets =
    mesh.AddOthers(received, [&](std::int64_t key) { return WithinBandOf(key, cuts, phases.Band()); });
  for (const auto& [label, volume] : beyondSlab)
    offsets[label] += volume;
  std::vector<vtkIdType> free;
  for (vtkIdType p = 0; p < owned->GetNumberOfPoints(); ++p)
    if (!seams.IsSeam(GlobalId(ids, p)))
      free.push_back(mesh.Place(GlobalId(ids, p)));
  vtkSmartPointer<vtkUnstructuredGrid> piece = mesh.Make(free);
  const int a = phases.Layout.Axis, first = phases.Layout.Cuts[phases.Me], last = phases.Layout.Cuts[phases.Me + 1] - 1;
  const int past = phases.Slices(1) + SeamSlices;
  SetWindow(piece, phases.Image, a, first - past, last + past);
  int extent[6];
  phases.Image->GetExtent(extent);
  for (const auto& [from, to] : { std::pair<int, int>(extent[2 * a], first - 1), { last + 1, extent[2 * a + 1] } })
    for (const auto& [label, volume] : VoxelVolumes(phases.Image, phases.ImageLabels, a, from, to))
      offsets[label] -= volume;
  SetVolumeOffsets(piece, offsets);
  vtkNew<vtkPoints> moved;
  const std::string error = phases.Run(piece, phases.Image, moved);
  if (error.empty())
  {
    vtkNew<vtkPoints> kept;
    kept->SetDataTypeToDouble();
    kept->SetNumberOfPoints(owned->GetNumberOfPoints());
    for (vtkIdType p = 0; p < owned->GetNumberOfPoints(); ++p)
      kept->SetPoint(p, moved->GetPoint(mesh.Place(GlobalId(ids, p))));
    owned->SetPoints(kept);
  }
  return error;
}

// The points this rank moves in the second phase, as places in `mesh`: those within the band of
// its upper cut on either side, less those sharing a tet with a point within the band of
// another cut (another rank moves those).
std::vector<vtkIdType> BandMovers(const Phases& phases, const RunMesh& mesh)
{
  const std::int64_t cut = phases.Layout.CutKeys[phases.Me];
  std::vector<std::int64_t> others;
  for (std::size_t c = 0; c < phases.Layout.CutKeys.size(); ++c)
    if (int(c) != phases.Me)
      others.push_back(phases.Layout.CutKeys[c]);
  std::vector<char> held(mesh.Places().size(), 0);
  for (const auto& tet : mesh.Tets())
  {
    if (std::any_of(tet.begin(), tet.end(), [&](vtkIdType p) { return WithinBandOf(mesh.KeyAt(p), others, phases.Band()); }))
      for (const vtkIdType p : tet)
        held[p] = 1;
  }
  std::vector<vtkIdType> movers;
  for (const auto& [id, p] : mesh.Places())
    if (std::abs(mesh.KeyAt(p) - cut) <= phases.Band() && !held[p])
      movers.push_back(p);
  std::sort(movers.begin(), movers.end());
  return movers;
}

// The second phase: the points within two cubes of this rank's upper cut, on both sides, among
// its tets and its upper neighbour's near that cut (`received`, as the first phase left them), the
// rest held; then every rank takes the places of its points moved. False on every rank where a
// rank's run failed (its error in `error`).
bool DeformBands(vtkMultiProcessController* controller, const Phases& phases, const BandTets& received, std::string& error)
{
  vtkNew<vtkTypeInt64Array> sendIds, allIds;
  vtkNew<vtkDoubleArray> sendPlaces, allPlaces;
  vtkUnstructuredGrid* owned = phases.Owned;
  if (owned->GetNumberOfCells() > 0 && phases.Me + 1 < phases.Ranks)
  {
    const std::int64_t cut = phases.Layout.CutKeys[phases.Me];
    const std::int64_t reach = ReachCubes * phases.Layout.CubeKeys;
    RunMesh mesh(owned->GetCellData()->GetArray(vtkCBC3DArrayNames::Label));
    auto near = [&](std::int64_t key) { return std::abs(key - cut) <= reach; };
    mesh.AddOwned(owned, phases.AxisKeys, near);
    mesh.AddOthers(received, near);
    const std::vector<vtkIdType> movers = BandMovers(phases, mesh);
    if (!movers.empty())
    {
      vtkSmartPointer<vtkUnstructuredGrid> band = mesh.Make(movers);
      // As far as the tets reach, so that those crossing the window's ends hold their corners.
      // Each tissue keeps the volume it has: the first phase made up, over the rank's slab, for
      // what the held seam lacked.
      const int slice = phases.Layout.Cuts[phases.Me + 1];
      const int slices = phases.Slices(ReachCubes);
      SetWindow(band, phases.Image, phases.Layout.Axis, slice - slices, slice + slices - 1);
      std::map<vtkTypeInt64, double> offsets = vtkCBC3DSeamPoints::TissueVolumes(band);
      int extent[6];
      phases.Image->GetExtent(extent);
      const int a = phases.Layout.Axis;
      for (const auto& [label, volume] : VoxelVolumes(phases.Image, phases.ImageLabels, a, extent[2 * a], extent[2 * a + 1]))
        offsets[label] -= volume;
      SetVolumeOffsets(band, offsets);
      vtkNew<vtkPoints> moved;
      error = phases.Run(band, phases.Image, moved);
      std::unordered_map<vtkIdType, vtkIdType> idAt;
      for (const auto& [id, p] : mesh.Places())
        idAt.emplace(p, id);
      for (std::size_t m = 0; error.empty() && m < movers.size(); ++m)
      {
        sendIds->InsertNextValue(idAt.at(movers[m]));
        for (int a = 0; a < 3; ++a)
          sendPlaces->InsertNextValue(moved->GetPoint(movers[m])[a]);
      }
    }
  }
  if (!vtkCBC3DPieces::AllAgree(controller, error.empty()))
    return false;
  controller->AllGatherV(sendIds, allIds);
  controller->AllGatherV(sendPlaces, allPlaces);
  std::unordered_map<vtkIdType, vtkIdType> sent;
  for (vtkIdType s = 0; s < allIds->GetNumberOfValues(); ++s)
    sent.emplace(vtkIdType(allIds->GetValue(s)), s);
  vtkDataArray* ids = owned->GetPointData()->GetArray(vtkCBC3DArrayNames::GlobalIds);
  for (vtkIdType p = 0; ids && p < owned->GetNumberOfPoints(); ++p)
  {
    const auto found = sent.find(GlobalId(ids, p));
    if (found != sent.end())
      owned->GetPoints()->SetPoint(p, allPlaces->GetPointer(3 * found->second));
  }
  return true;
}

void AddDisplacement(vtkUnstructuredGrid* owned, vtkPoints* start)
{
  vtkNew<vtkDoubleArray> displacement;
  displacement->SetName(vtkCBC3DArrayNames::Displacement);
  displacement->SetNumberOfComponents(3);
  displacement->SetNumberOfTuples(owned->GetNumberOfPoints());
  for (vtkIdType p = 0; p < owned->GetNumberOfPoints(); ++p)
  {
    double from[3], to[3];
    start->GetPoint(p, from);
    owned->GetPoint(p, to);
    displacement->SetTuple3(p, to[0] - from[0], to[1] - from[1], to[2] - from[2]);
  }
  owned->GetPointData()->AddArray(displacement);
}
} // namespace

namespace vtkCBC3DRankDeformation
{
bool DeformAcrossRanks(vtkMultiProcessController* controller, const Layout& layout, vtkImageData* image,
  vtkDataArray* imageLabels, vtkUnstructuredGrid* owned, const RunDeformation& run, std::string& error)
{
  const Phases phases{ layout, controller->GetLocalProcessId(), controller->GetNumberOfProcesses(), image,
    imageLabels, owned, vtkCBC3DSeamPoints::AxisKeys(owned, layout.Axis), run };
  const Seams seams = vtkCBC3DSeamPoints::FindSeams(controller, owned, layout.Axis, layout.CutKeys, layout.CubeKeys);
  const std::map<vtkTypeInt64, double> beyondSlab =
    vtkCBC3DSeamPoints::TissueBeyondSlab(controller, owned, layout.Axis, layout.CutKeys);
  vtkNew<vtkPoints> start;
  start->SetDataTypeToDouble();
  if (owned->GetPoints())
    start->DeepCopy(owned->GetPoints());
  // Each slab first, its seam points held, with its neighbours' undeformed tets about it; then
  // the bands about the cuts, from the slabs' tets.
  {
    BandTets undeformed;
    vtkCBC3DBandTets::Share(controller, owned, phases.AxisKeys, layout.CutKeys, layout.CubeKeys, undeformed);
    if (owned->GetNumberOfCells() > 0)
      error = DeformOwnTets(phases, seams, undeformed, beyondSlab);
  }
  if (!vtkCBC3DPieces::AllAgree(controller, error.empty()))
    return false;
  BandTets deformed;
  vtkCBC3DBandTets::Share(controller, owned, phases.AxisKeys, layout.CutKeys, layout.CubeKeys, deformed);
  if (!DeformBands(controller, phases, deformed, error))
    return false;
  AddDisplacement(owned, start);
  return true;
}
} // namespace vtkCBC3DRankDeformation
