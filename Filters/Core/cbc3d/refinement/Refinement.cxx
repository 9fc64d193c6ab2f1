#include "cbc3d/refinement/Refinement.h"

#include "cbc3d/lattice/BCCLattice.h"

#include "cbc3d/base/MeshFaces.h"
#include "cbc3d/base/Parallel.h"
#include "cbc3d/lattice/RedGreenMesh.h"
#include "cbc3d/refinement/BoundaryCoverage.h"
#include "cbc3d/refinement/CoveragePasses.h"
#include "cbc3d/refinement/EdgeLimits.h"
#include "cbc3d/refinement/KeptComponents.h"
#include "cbc3d/refinement/LabelledMesh.h"
#include "cbc3d/refinement/RefinementInputs.h"
#include "cbc3d/refinement/SurfaceEars.h"
#include "cbc3d/refinement/TetBudget.h"
#include "cbc3d/sampling/TetVoxelSampler.h"
#include "cbc3d/sampling/TissueComponents.h"
#include "cbc3d/soundlabels/ImageRegions.h"
#include "cbc3d/soundlabels/ManifoldRepair.h"
#include "cbc3d/soundlabels/SoundLabels.h"

#include <algorithm>
#include <atomic>
#include <functional>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>

namespace cbc3d
{
namespace
{

// Rounds of refining again where the sound labels left tets beyond an edge limit.
constexpr int EdgeLimitRounds = 3;

// The share of a tet budget the passes aim at, how many times refinement may start again aiming
// lower, and how far under the share it went over the next aim goes.
constexpr double BudgetAim = 0.95;
constexpr int BudgetAttempts = 3;
constexpr double BudgetRetryMargin = 0.98;

// Bytes per tet at peak: the hierarchy, the final tets, their samples and the VTK output.
constexpr double BytesPerTet = 400.0;

// Which leaves to split red for fidelity: those whose tets cross the boundary of a tissue below
// the target, and those holding a tissue component that no tet of its tissue represents yet.
std::vector<char> MarkForFidelity(const LabelImage& image, const TissueComponents& components,
  const RefinementParams& params, const LabelledMesh& mesh,
  const std::map<std::int32_t, TissueFidelity>& fidelity, const std::vector<char>& componentInMesh,
  std::size_t leaves)
{
  auto isFailing = [&](std::int32_t label) {
    const auto found = fidelity.find(label);
    const double target = params.FidelityOf(label);
    return found != fidelity.end() && (found->second.F1 < target || found->second.F2 < target);
  };
  std::vector<char> marked(leaves, 0);
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const auto& counts = mesh.Counts[t].Counts;
    if (counts.size() < 2)
    {
      continue;
    }
    for (const auto& entry : counts)
    {
      if (isFailing(entry.first))
      {
        marked[mesh.Source[t]] = 1;
        break;
      }
    }
  }
  // The tets holding a component that is missing from the mesh (rare: most runs are skipped).
  for (const TissueComponents::Run& run : components.Runs)
  {
    if (componentInMesh[run.Component] || IsSmall(components, run.Component, params.MinimumComponentVoxels))
    {
      continue;
    }
    for (std::int64_t v = run.First; v <= run.Last; ++v)
    {
      const std::int32_t owner = mesh.OwnerOf(v);
      if (owner >= 0)
      {
        marked[mesh.Source[owner]] = 1;
      }
    }
  }
  return marked;
}

// The tissue tets, their points renumbered in first-use order, and each one's red level. Sized
// exactly: this mesh and the hierarchy together are the refinement's peak.
void KeepTissueTets(const LabelImage& image, const RedGreenMesh& hierarchy, const LabelledMesh& mesh,
  TetMesh& out, RefinementResult& result)
{
  std::vector<PointId> newId(hierarchy.Points().size(), -1);
  std::size_t kept = 0;
  PointId points = 0;
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    if (!IsTissueLabel(image, mesh.Labels[t]))
      continue;
    ++kept;
    for (const PointId p : mesh.Tets[t])
      if (newId[p] < 0)
        newId[p] = points++;
  }
  out.Points.resize(std::size_t(points));
  for (std::size_t p = 0; p < newId.size(); ++p)
    if (newId[p] >= 0)
      out.Points[newId[p]] = hierarchy.Points()[p];
  out.Tets.reserve(kept);
  out.Labels.reserve(kept);
  result.Levels.reserve(kept);
  for (std::size_t t = 0; t < mesh.Tets.size(); ++t)
  {
    const std::int32_t label = mesh.Labels[t];
    if (!IsTissueLabel(image, label))
      continue;
    Tet tet;
    for (int v = 0; v < 4; ++v)
      tet[v] = newId[mesh.Tets[t][v]];
    out.Tets.push_back(tet);
    out.Labels.push_back(label);
    const int level = hierarchy.Reds()[mesh.Source[t]].Level;
    result.Levels.push_back(static_cast<std::uint8_t>(level));
    result.DeepestLevel = std::max(result.DeepestLevel, level);
  }
}

// Why the passes ended. The words come last (StopReason), when the fidelity after the sound
// labels is known as well.
struct PassesEnd
{
  enum Kind
  {
    NoRefinementAsked, // fidelity 0
    TargetsReached,    // no tissue's fidelity (nor the boundary distance) wants a split
    AtMinimumEdge,     // splits are wanted, at tets that may not be split
    MemoryLimit,       // the splits would pass it
    TetBudget          // no more splits fit the budget of tets
  };
  Kind End = TargetsReached;
  std::int64_t ExpectedTets = 0; // with MemoryLimit: the tets the splits would have made
};

// How a stop reason begins when no tissue's fidelity wants a split.
const std::string ReachedFidelity = "every tissue reached the fidelity target";

// Why refinement ended, in words: how the passes ended, how refining for the boundary distance
// did (`coverage`: whether there was any), and whether making the labels sound took a tissue
// below the fidelity target after the passes had reached it (the 3 mm head's CSF and grey matter).
std::string StopReason(const PassesEnd& passes, bool coverage, const CoverageProgress& progress, bool belowTarget)
{
  std::ostringstream reason;
  switch (passes.End)
  {
    case PassesEnd::NoRefinementAsked:
      return "no refinement asked (fidelity 0)";
    case PassesEnd::AtMinimumEdge:
      return "the tets left to refine are at the minimum edge length";
    case PassesEnd::MemoryLimit:
      reason << "stopped before exceeding the memory limit (about " << passes.ExpectedTets << " tets)";
      return reason.str();
    case PassesEnd::TetBudget:
      return "the tet budget is spent";
    case PassesEnd::TargetsReached:
      break;
  }
  reason << ReachedFidelity;
  if (coverage)
    reason << (progress.Stalled ? ", and refining for the boundary distance stopped gaining" : " and the boundary distance");
  if (belowTarget)
    reason << "; making the labels sound took some below it";
  return reason.str();
}

struct PassLimits
{
  double MinimumEdge;   // the floor of splits for fidelity and the boundary distance
  double EdgeLimitFloor; // the floor of splits for an edge limit: the user's, else none
  std::size_t MemoryBytes;
};

// Unmarks the marked leaves at the depth limit (a split would make edges shorter than the floor:
// limits.EdgeLimitFloor for leaves marked for an edge limit, else limits.MinimumEdge) and counts
// the rest; `anyWanted` becomes true where any leaf was marked.
std::size_t KeepSplittable(const RedGreenMesh& hierarchy, const PassLimits& limits, std::vector<char>& marked,
  bool& anyWanted)
{
  std::size_t splits = 0;
  for (std::size_t red = 0; red < marked.size(); ++red)
  {
    if (!marked[red])
    {
      continue;
    }
    anyWanted = true;
    const double floor = marked[red] == MarkedForEdgeLimit ? limits.EdgeLimitFloor : limits.MinimumEdge;
    if (!(hierarchy.ShortestEdge(red) / 2.0 >= floor * (1.0 - 1e-9)))
      marked[red] = 0;
    splits += marked[red] != 0;
  }
  return splits;
}
// How small a tet may get, and how much memory the mesh may take.


// Marks the reds that fidelity or coverage wants split (and that may be) and the edges coverage
// bisects, and splits them; false, with how the passes ended in `end`, when there is nothing
// left to split or the splits would pass the memory limit.
bool SplitOnePass(const LabelImage& image, const TissueComponents& components, const RefinementParams& params,
  const BoundaryCoverage* coverage, double distance, const PassLimits& limits,
  const std::map<std::int32_t, TissueFidelity>& fidelity, const std::vector<char>& componentInMesh,
  const LabelledMesh& mesh, RedGreenMesh& hierarchy, CoverageProgress& progress, TetBudget* budget, PassesEnd& end)
{
  std::vector<char> marked = MarkForFidelity(image, components, params, mesh, fidelity, componentInMesh,
    hierarchy.Reds().size());
  MarkForMaximumEdge(image, params, hierarchy, mesh, marked);
  std::vector<std::pair<PointId, PointId>> bisect;
  const RankPasses* ranks = params.Ranks.get();
  const bool measure = coverage && !progress.Stalled;
  const bool coverageWanted =
    measure && MarkForCoverage(image, *coverage, distance, hierarchy, mesh, limits.MinimumEdge, progress, marked, bisect, ranks);
  if (coverage && !measure && ranks)
  {
    double far = 0.0, largest = 0.0; // one call a pass on every rank, measuring or not
    ranks->SumAndMax(far, largest);
  }
  bool anyWanted = coverageWanted;
  std::size_t splits = KeepSplittable(hierarchy, limits, marked, anyWanted);
  bool fits = true;
  if (budget && (splits > 0 || !bisect.empty()))
    splits = budget->Keep(image, mesh, hierarchy, marked, bisect, params.NumberOfThreads, fits);
  if (!fits)
  {
    end.End = PassesEnd::TetBudget;
    return false;
  }
  if (splits == 0 && bisect.empty())
  {
    end.End = anyWanted ? PassesEnd::AtMinimumEdge : PassesEnd::TargetsReached;
    return false;
  }
  // Each red split makes 8 tets of one; closure adds some more.
  const double expectedTets = double(mesh.Tets.size()) + 10.0 * double(splits) + 6.0 * double(bisect.size());
  if (expectedTets * BytesPerTet > double(limits.MemoryBytes))
  {
    end.End = PassesEnd::MemoryLimit;
    end.ExpectedTets = std::llround(expectedTets);
    return false;
  }
  for (std::size_t red = 0; red < marked.size(); ++red)
  {
    if (marked[red])
    {
      hierarchy.SplitRed(red);
    }
  }
  for (const auto& [a, b] : bisect)
  {
    hierarchy.SplitEdge(a, b);
  }
  return true;
}

// One refinement of the (ringed) lattice, the passes aiming at `budgetAim` of the tet budget.
Status RefineToAim(const LabelImage& image, const TissueComponents& components, const ImageRegions* regions,
  const TetMesh& ringed, const RefinementParams& params, double budgetAim, TetMesh& out, RefinementResult& result,
  const Progress& progress)
{
  out = TetMesh();
  result = RefinementResult();
  const double minimumEdge = params.MinimumEdgeLength > 0.0
    ? params.MinimumEdgeLength
    : DefaultMinimumEdgeLength(image.Spacing);
  const std::size_t memoryLimit =
    params.MemoryLimitBytes > 0 ? params.MemoryLimitBytes : PhysicalMemoryBytes() / 2;
  RedGreenMesh hierarchy(ringed);
  const std::unique_ptr<BoundaryCoverage> coverage = MakeCoverage(image, components, params, hierarchy, result);
  LabelledMesh mesh;
  std::map<std::int32_t, TissueFidelity> fidelity;
  std::vector<char> componentInMesh;
  CoverageProgress coverageProgress;
  PassesEnd passesEnd;
  // The passes aim a little under the budget: making the labels sound moves the count.
  const std::unique_ptr<TetBudget> budget = params.MaximumTets > 0
    ? std::make_unique<TetBudget>(std::llround(budgetAim * double(params.MaximumTets)))
    : nullptr;
  const int expectedPasses = 2 + static_cast<int>(std::ceil(std::log2(
    std::max(1.0, hierarchy.ShortestEdge(0) / minimumEdge))));

  for (int round = 0;; ++round)
  {
    for (int pass = 0;; ++pass)
    {
      const double done = std::min(0.95, double(pass + 1) / double(expectedPasses + 1));
      const std::function<bool()> keepGoing = [&] { return KeepGoing(progress, done); };
      if (!hierarchy.Close(keepGoing) || !SampleAll(image, hierarchy, params.NumberOfThreads, mesh, keepGoing))
      {
        return Status::Aborted();
      }
      fidelity = MeasureFidelity(image, components, params.MinimumComponentVoxels, mesh, params.NumberOfThreads,
        componentInMesh, params.Ranks.get(), &hierarchy.Points());
      if (!params.AsksForRefinement())
      {
        passesEnd.End = PassesEnd::NoRefinementAsked;
        break;
      }

      const bool split = SplitOnePass(image, components, params, coverage.get(), result.BoundaryDistance,
        PassLimits{ minimumEdge, params.MinimumEdgeLength, memoryLimit }, fidelity, componentInMesh, mesh,
        hierarchy, coverageProgress, budget.get(), passesEnd);
      // Over ranks, a rank with nothing to split passes on while another splits.
      if (params.Ranks ? !params.Ranks->Any(split) : !split)
      {
        break;
      }
      ++result.Passes;
    }

    ResolveOwners(mesh, params.NumberOfThreads);
    // Spikes on the surface would keep their tips off the image boundary through deformation.
    const auto across = FaceNeighbours(mesh.Tets, hierarchy.Points().size(), params.NumberOfThreads);
    bool earsRemoved = RemoveSurfaceEars(mesh.Tets, across, hierarchy.Points().size(), mesh.Labels,
                         [&](std::int32_t label) { return IsTissueLabel(image, label); }, NoLabel) > 0;
    if (params.Ranks ? params.Ranks->Any(earsRemoved) : earsRemoved)
    {
      fidelity = MeasureFidelity(image, components, params.MinimumComponentVoxels, mesh, params.NumberOfThreads,
        componentInMesh, params.Ranks.get(), &hierarchy.Points());
    }

    fidelity = KeepComponentsAndMakeSound(image, components, regions, params, hierarchy.Points(), across, mesh,
      componentInMesh, result.Relabelled);

    result.OverlongTets = CountOverlongEdges(hierarchy.Points(), mesh.Tets, mesh.Labels, image, params);
    // Tets that making the labels sound gave to a tissue may pass its edge limit: split them and
    // refine again, from a fresh sampling (the owners are renumbered by now).
    bool again = result.OverlongTets > 0 && round < EdgeLimitRounds && SplitOverlongTets(image, params, hierarchy, mesh);
    if (params.Ranks)
    {
      again = params.Ranks->Any(again); // every rank refines again, or none
    }
    if (!again)
    {
      break;
    }
    mesh = LabelledMesh();
  }
  KeepTissueTets(image, hierarchy, mesh, out, result);
  for (const auto& entry : fidelity)
  {
    result.Tissues.push_back(entry.second);
  }
  result.LargestBoundaryGap = coverageProgress.LargestGap;
  const bool belowTarget = std::any_of(result.Tissues.begin(), result.Tissues.end(),
    [&](const TissueFidelity& t) { return t.F1 < params.FidelityOf(t.Label) || t.F2 < params.FidelityOf(t.Label); });
  result.StopReason = StopReason(passesEnd, coverage != nullptr, coverageProgress, belowTarget);
  // Over ranks, a rank whose piece holds only the edge of a tissue may keep no tet.
  const bool none = out.Tets.empty();
  if (params.Ranks ? !params.Ranks->Any(!none) : none)
  {
    return Status::Error("no tet holds a majority of tissue voxels; use a smaller lattice size");
  }
  if (progress)
  {
    progress(1.0);
  }
  return Status::Ok();
}
} // namespace

bool RefinementParams::AsksForRefinement() const
{
  const auto positive = [](const std::map<std::int32_t, double>& values) {
    return std::any_of(values.begin(), values.end(), [](const auto& entry) { return entry.second > 0.0; });
  };
  return this->Fidelity > 0.0 || positive(this->FidelityByTissue) || this->MaximumEdge.Any();
}

Status RefineMesh(const LabelImage& image, const TetMesh& lattice, const RefinementParams& params,
  TetMesh& out, RefinementResult& result, const Progress& progress)
{
  out = TetMesh();
  result = RefinementResult();
  // Over ranks, inputs that stop one rank stop every rank, a rank without tissue as well.
  const auto stops = [&params](const Status& status) {
    return params.Ranks ? params.Ranks->Any(!status.IsOk()) : !status.IsOk();
  };
  const Status valid = ValidateInputs(image, lattice, params);
  if (stops(valid))
  {
    return valid.IsOk() ? Status::Error("another rank's inputs to refinement are not valid") : valid;
  }
  TissueComponents components = FindTissueComponents(image);
  const Status present = CheckTissuesPresent(components, params);
  if (stops(present))
  {
    return present;
  }
  // The image's regions, for the sound labels: its components, and its cavities.
  std::unique_ptr<ImageRegions> regions;
  BackgroundComponents gaps = params.SoundLabels ? FindBackgroundComponents(image) : BackgroundComponents();
  if (params.Ranks)
  {
    params.Ranks->JoinComponents(image, components, nullptr);
    if (params.SoundLabels)
      params.Ranks->JoinComponents(image, gaps, &gaps.TouchesBorder);
  }
  if (params.SoundLabels)
    regions = std::make_unique<ImageRegions>(
      FindImageRegions(components, std::move(gaps), params.MinimumComponentVoxels, NoLabel));
  // Sound labels need background on both sides of a thin sheet of tissue to thicken it into.
  TetMesh ringed = lattice;
  if (params.SoundLabels)
    AddBackgroundRing(image, ringed);
  // Making the labels sound after the passes moves the count, most on coarse meshes: where the
  // mesh passes the budget, refinement starts again from the same lattice and components,
  // aiming lower by the share it went over.
  double aim = BudgetAim;
  for (int attempt = 0;; ++attempt)
  {
    const Status status = RefineToAim(image, components, regions.get(), ringed, params, aim, out, result, progress);
    const auto tets = static_cast<std::int64_t>(out.Tets.size());
    if (!status.IsOk() || params.MaximumTets <= 0 || tets <= params.MaximumTets || attempt == BudgetAttempts)
    {
      return status;
    }
    aim *= BudgetRetryMargin * double(params.MaximumTets) / double(tets);
  }
}
} // namespace cbc3d
