#include "vtkCBC3DPieces.h"

#include "vtkCBC3DArrayNames.h"
#include "vtkCBC3DComponentJoin.h"
#include "vtkCBC3DNIfTIReader.h"

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/refinement/RankPasses.h"

#include <vtkAlgorithm.h>
#include <vtkArrayDispatch.h>
#include <vtkCommunicator.h>
#include <vtkDataArrayRange.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkGhostCellsGenerator.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationDoubleVectorKey.h>
#include <vtkInformationExecutivePortKey.h>
#include <vtkMatrix3x3.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

namespace vtkCBC3DPieces
{
namespace
{
// The cuts between `pieces` slabs of `count` slices from `first`, each slab holding about an even
// share of the weights (one per slice), and none thinner than `thinnest` slices.
std::vector<int> WeightedCuts(int first, int count, int pieces, const double* weights, int thinnest)
{
  double total = 0.0;
  for (int s = 0; s < count; ++s)
    total += weights[s];
  std::vector<int> cuts(pieces + 1, first);
  cuts[pieces] = first + count;
  double below = 0.0; // the weight of the slices before slice s
  for (int s = 0, r = 1; s < count && r < pieces; ++s)
  {
    // The cut goes before the first slice whose end passes the share, or after it where that
    // end lies nearer the share.
    for (; r < pieces && below + weights[s] >= total * r / pieces; ++r)
      cuts[r] = first + s + (below + weights[s] - total * r / pieces < total * r / pieces - below ? 1 : 0);
    below += weights[s];
  }
  for (int r = 1; r < pieces; ++r)
    cuts[r] = std::max(cuts[r], cuts[r - 1] + thinnest);
  for (int r = pieces - 1; r >= 1; --r)
    cuts[r] = std::min(cuts[r], cuts[r + 1] - thinnest);
  return cuts;
}
} // namespace

SlabPlan PlanSlabs(const int wholeExtent[6], const double spacing[3], double h, double haloCubes, int pieces,
  int piece, const std::vector<double>& boundaryPerSlice)
{
  SlabPlan plan;
  plan.Pieces = std::max(1, pieces);
  plan.Piece = piece;
  double longest = -1.0;
  for (int a = 2; a >= 0; --a) // ties go to z, the slowest axis in memory
  {
    const double length = (wholeExtent[2 * a + 1] - wholeExtent[2 * a] + 1) * spacing[a];
    if (length > longest)
    {
      longest = length;
      plan.Axis = a;
    }
  }
  const int first = wholeExtent[2 * plan.Axis];
  const std::int64_t count = std::int64_t(wholeExtent[2 * plan.Axis + 1]) - first + 1;
  int dims[3], before = 0; // the slices along the axes before the plan's, in boundaryPerSlice
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = wholeExtent[2 * a + 1] - wholeExtent[2 * a] + 1;
    before += a < plan.Axis ? dims[a] : 0;
  }
  const double boundary = boundaryPerSlice.size() == std::size_t(dims[0]) + dims[1] + dims[2]
    ? std::accumulate(boundaryPerSlice.begin() + before, boundaryPerSlice.begin() + before + count, 0.0)
    : 0.0;
  if (boundary > 0.0)
  {
    const int thinnest = int(std::min<std::int64_t>(
      count / plan.Pieces, std::int64_t(std::ceil(MinimumSlabCubes * h / spacing[plan.Axis]))));
    plan.Cuts = WeightedCuts(first, int(count), plan.Pieces, boundaryPerSlice.data() + before, thinnest);
  }
  else
  {
    for (int r = 0; r <= plan.Pieces; ++r)
      plan.Cuts.push_back(first + int(count * r / plan.Pieces));
  }
  plan.HaloVoxels = int(std::ceil(haloCubes * h / spacing[plan.Axis])) + 1;
  return plan;
}

void PieceExtent(const SlabPlan& plan, const int wholeExtent[6], int extent[6])
{
  std::copy(wholeExtent, wholeExtent + 6, extent);
  const int a = plan.Axis;
  extent[2 * a] = std::max(wholeExtent[2 * a], plan.Cuts[plan.Piece] - plan.HaloVoxels);
  extent[2 * a + 1] = std::min(wholeExtent[2 * a + 1], plan.Cuts[plan.Piece + 1] - 1 + plan.HaloVoxels);
}

namespace
{
// Which slices, rows and columns hold a voxel that is not background.
struct FindTissue
{
  template <typename Array>
  void operator()(Array* labels, const std::vector<vtkTypeInt64>& background, const int dims[3],
    std::vector<char> (&occupied)[3])
  {
    const auto values = vtk::DataArrayValueRange<1>(labels);
    vtkIdType v = 0;
    for (int k = 0; k < dims[2]; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i, ++v)
        {
          const auto value = vtkTypeInt64(values[v]);
          if (std::find(background.begin(), background.end(), value) == background.end())
          {
            occupied[0][i] = occupied[1][j] = occupied[2][k] = 1;
          }
        }
  }
};
} // namespace

bool TissueBox(vtkImageData* image, vtkDataArray* labels, const std::vector<vtkTypeInt64>& background,
  int lower[3], int upper[3])
{
  int dims[3], extent[6];
  image->GetDimensions(dims);
  image->GetExtent(extent);
  std::vector<char> occupied[3];
  for (int a = 0; a < 3; ++a)
  {
    occupied[a].assign(std::max(0, dims[a]), 0);
  }
  if (labels && labels->GetNumberOfTuples() == image->GetNumberOfPoints())
  {
    FindTissue find;
    if (!vtkArrayDispatch::Dispatch::Execute(labels, find, background, dims, occupied))
    {
      find(labels, background, dims, occupied);
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    const auto first = std::find(occupied[a].begin(), occupied[a].end(), 1);
    if (first == occupied[a].end())
    {
      return false;
    }
    const auto last = std::find(occupied[a].rbegin(), occupied[a].rend(), 1);
    lower[a] = extent[2 * a] + int(first - occupied[a].begin());
    upper[a] = extent[2 * a] + int(occupied[a].rend() - last) - 1;
  }
  return true;
}

bool AgreeOnTissueBox(vtkMultiProcessController* controller, bool has, const int lower[3],
  const int upper[3], int wholeLower[3], int wholeUpper[3])
{
  // Upper bounds travel negated, so one minimum gives both ends of the box.
  int mine[6], all[6];
  for (int a = 0; a < 3; ++a)
  {
    mine[a] = has ? lower[a] : VTK_INT_MAX;
    mine[3 + a] = has ? -upper[a] : VTK_INT_MAX;
  }
  controller->AllReduce(mine, all, 6, vtkCommunicator::MIN_OP);
  for (int a = 0; a < 3; ++a)
  {
    wholeLower[a] = all[a];
    wholeUpper[a] = -all[3 + a];
  }
  return all[0] != VTK_INT_MAX;
}

bool AllAgree(vtkMultiProcessController* controller, bool yes)
{
  int mine = yes ? 1 : 0, all = 0;
  controller->AllReduce(&mine, &all, 1, vtkCommunicator::MIN_OP);
  return all == 1;
}

std::shared_ptr<const cbc3d::RankPasses> MakeRankPasses(
  vtkMultiProcessController* controller, const SlabPlan& plan, vtkImageData* image)
{
  auto ranks = std::make_shared<cbc3d::RankPasses>();
  const int a = plan.Axis;
  const double spacing = image->GetSpacing()[a];
  const int first = image->GetExtent()[2 * a];
  // A third of a voxel past the middle between two slices: no voxel centre lies there, nor a
  // lattice point or tet centre (those sit at binary fractions of the voxel size).
  auto border = [&](int slice) { return spacing * (slice - first - 0.5 + 1.0 / 3.0); };
  const double infinity = std::numeric_limits<double>::infinity();
  ranks->Axis = a;
  ranks->Lower = plan.Piece > 0 ? border(plan.Cuts[plan.Piece]) : -infinity;
  ranks->Upper = plan.Piece + 1 < plan.Pieces ? border(plan.Cuts[plan.Piece + 1]) : infinity;
  ranks->SumAndMax = [controller](double& sum, double& largest) {
    double mine[2] = { sum, largest }, all[2];
    controller->AllReduce(mine, all, 1, vtkCommunicator::SUM_OP);
    controller->AllReduce(mine + 1, all + 1, 1, vtkCommunicator::MAX_OP);
    sum = all[0];
    largest = all[1];
  };
  ranks->Any = [controller](bool yes) {
    int mine = yes ? 1 : 0, all = 0;
    controller->AllReduce(&mine, &all, 1, vtkCommunicator::MAX_OP);
    return all != 0;
  };
  ranks->AllValues = [controller](const std::vector<double>& values) {
    vtkNew<vtkDoubleArray> mine, all;
    mine->SetNumberOfValues(vtkIdType(values.size()));
    std::copy(values.begin(), values.end(), mine->GetPointer(0));
    controller->AllGatherV(mine, all);
    return std::vector<double>(all->GetPointer(0), all->GetPointer(0) + all->GetNumberOfValues());
  };
  int extent[6];
  image->GetExtent(extent);
  ranks->JoinComponents = [controller, plan, extent](const cbc3d::LabelImage& piece,
                            cbc3d::RunComponents& components, std::vector<char>* outside) {
    vtkCBC3DComponentJoin::Join(controller, plan, extent, piece, components, outside);
  };
  return ranks;
}

LatticeKeys::LatticeKeys(vtkImageData* image, const int wholeLower[3], double h)
{
  image->GetOrigin(this->Origin);
  const double* spacing = image->GetSpacing();
  // The core's lattice takes the direction made orthonormal; so do the keys.
  cbc3d::LabelImage frame;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      frame.Direction(r, c) = image->GetDirectionMatrix()->GetElement(r, c);
    }
  }
  cbc3d::OrthonormalizeDirection(frame);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      this->Direction[3 * r + c] = frame.Direction(r, c);
    }
    // The lattice's corner lies a cube before the tissue box (cbc3d's lattice frame).
    this->Corner[r] = spacing[r] * wholeLower[r] - h;
  }
  this->Unit = h / 256.0;
}

bool LatticeKeys::Key(const double point[3], std::array<std::int64_t, 3>& key) const
{
  for (int a = 0; a < 3; ++a)
  {
    double along = 0.0; // the point along image axis a, mm from structured index 0
    for (int r = 0; r < 3; ++r)
    {
      along += this->Direction[3 * r + a] * (point[r] - this->Origin[r]);
    }
    const double steps = (along - this->Corner[a]) / this->Unit;
    key[a] = std::llround(steps);
    if (std::abs(steps - double(key[a])) > 0.05)
    {
      return false;
    }
  }
  return true;
}

std::int64_t LatticeKeys::CutKey(int axis, int slice, double spacing) const
{
  return std::llround((spacing * (slice - 0.5) - this->Corner[axis]) / this->Unit);
}

namespace
{
constexpr int KeyBits = 21;
constexpr std::int64_t KeyOffset = 4 * 256; // four cubes below the corner: the background ring
}

bool PackKey(const std::array<std::int64_t, 3>& key, vtkIdType& id)
{
  std::int64_t packed = 0;
  for (int a = 2; a >= 0; --a)
  {
    const std::int64_t shifted = key[a] + KeyOffset;
    if (shifted < 0 || shifted >= (std::int64_t(1) << KeyBits))
    {
      return false;
    }
    packed = (packed << KeyBits) | shifted;
  }
  id = vtkIdType(packed);
  return true;
}

std::array<std::int64_t, 3> UnpackKey(vtkIdType id)
{
  std::array<std::int64_t, 3> key;
  const std::int64_t mask = (std::int64_t(1) << KeyBits) - 1;
  for (int a = 0; a < 3; ++a)
  {
    key[a] = ((std::int64_t(id) >> (KeyBits * a)) & mask) - KeyOffset;
  }
  return key;
}

bool AddLatticeKeys(vtkUnstructuredGrid* mesh, const LatticeKeys& keys, std::string& error)
{
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName(LatticeKeyName);
  ids->SetNumberOfValues(mesh->GetNumberOfPoints());
  std::array<std::int64_t, 3> key;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double point[3];
    mesh->GetPoint(p, point);
    vtkIdType id = 0;
    if (!keys.Key(point, key) || !PackKey(key, id))
    {
      error = "a lattice point falls off the grid of lattice keys (refinement deeper than 7 "
              "levels, or an image wider than 8,000 lattice cubes)";
      return false;
    }
    ids->SetValue(p, id);
  }
  mesh->GetPointData()->AddArray(ids);
  return true;
}

std::vector<double> BoundaryPerSlice(vtkInformation* inputInfo)
{
  // Up through the filters of one input each between the reader and here: ParaView puts its
  // vtkPVPostFilter after every source, and the executives pass on only the keys they know.
  vtkInformationDoubleVectorKey* key = vtkCBC3DNIfTIReader::BOUNDARY_PER_SLICE();
  for (vtkInformation* info = inputInfo; info;)
  {
    if (info->Has(key))
      return std::vector<double>(info->Get(key), info->Get(key) + info->Length(key));
    vtkExecutive* producer = vtkExecutive::PRODUCER()->GetExecutive(info);
    vtkAlgorithm* algorithm = producer ? producer->GetAlgorithm() : nullptr;
    info = algorithm && algorithm->GetNumberOfInputPorts() == 1 && algorithm->GetNumberOfInputConnections(0) == 1
      ? algorithm->GetInputInformation(0, 0)
      : nullptr;
  }
  return {};
}

bool AddGhostCells(vtkMultiProcessController* controller, vtkInformation* outInfo, vtkUnstructuredGrid* output)
{
  const int asked = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS())
    : 0;
  int levels = 0;
  controller->AllReduce(&asked, &levels, 1, vtkCommunicator::MAX_OP);
  if (levels <= 0)
    return true;
  vtkNew<vtkUnstructuredGrid> piece;
  piece->ShallowCopy(output);
  vtkNew<vtkGhostCellsGenerator> ghosts;
  ghosts->SetController(controller);
  ghosts->BuildIfRequiredOff();
  ghosts->SetNumberOfGhostLayers(levels);
  ghosts->SetInputData(piece);
  const bool made = ghosts->GetExecutive()->Update() != 0;
  if (made)
  {
    output->ShallowCopy(ghosts->GetOutputDataObject(0));
    output->GetFieldData()->ShallowCopy(piece->GetFieldData());
  }
  return AllAgree(controller, made);
}
} // namespace vtkCBC3DPieces
