#include "cbc3d/lattice/BCCLattice.h"

#include "cbc3d/base/Parallel.h"
#include "cbc3d/base/TetGeometry.h"
#include "cbc3d/sampling/TetVoxelSampler.h"

#include <Eigen/LU>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>

namespace cbc3d
{
namespace
{
// Bytes per lattice cube at peak: the 12 candidate slots, the vertex map, and the kept tets
// and points in the core mesh and again in the VTK output (an upper bound: all kept).
constexpr double BytesPerCube = 1300.0;

// The lattice in the image-axis frame: millimetres along the image axes from the image origin.
struct LatticeFrame
{
  Eigen::Vector3d CornerOrigin; // position of corner (0,0,0)
  double H = 0.0;               // cube edge
  std::array<std::int64_t, 3> Cubes = { 0, 0, 0 };

  std::int64_t CubeCount() const { return this->Cubes[0] * this->Cubes[1] * this->Cubes[2]; }
  std::int64_t CornerCount() const
  {
    return (this->Cubes[0] + 1) * (this->Cubes[1] + 1) * (this->Cubes[2] + 1);
  }
  std::int64_t CornerId(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return i + (this->Cubes[0] + 1) * (j + (this->Cubes[1] + 1) * k);
  }
  // Centres are numbered after the corners, in cube order.
  std::int64_t CentreId(std::int64_t cube) const { return this->CornerCount() + cube; }

  // Position (image-axis frame) of a vertex id.
  Eigen::Vector3d Position(std::int64_t id) const
  {
    const bool centre = id >= this->CornerCount();
    const std::int64_t local = centre ? id - this->CornerCount() : id;
    const std::int64_t nx = this->Cubes[0] + (centre ? 0 : 1);
    const std::int64_t ny = this->Cubes[1] + (centre ? 0 : 1);
    const Eigen::Vector3d grid(double(local % nx), double((local / nx) % ny), double(local / (nx * ny)));
    const double shift = centre ? 0.5 : 0.0;
    return this->CornerOrigin + this->H * (grid.array() + shift).matrix();
  }

  // The tet in slot (cube, axis, edge): the centres of this cube and of its neighbour along
  // `axis`, and one edge of the square face they share. False when the neighbour is outside.
  bool SlotTet(std::int64_t cube, int axis, int edge, std::array<std::int64_t, 4>& ids) const
  {
    std::array<std::int64_t, 3> c = { cube % this->Cubes[0], (cube / this->Cubes[0]) % this->Cubes[1],
      cube / (this->Cubes[0] * this->Cubes[1]) };
    if (c[axis] + 1 >= this->Cubes[axis])
    {
      return false;
    }
    std::array<std::int64_t, 3> step = { 0, 0, 0 };
    step[axis] = 1;
    const std::int64_t neighbour = cube + step[0] + this->Cubes[0] * (step[1] + this->Cubes[1] * step[2]);
    // The face's corners, walked around the square: (0,0) (1,0) (1,1) (0,1) in the two other axes.
    static constexpr int square[5][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 }, { 0, 0 } };
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    std::array<std::int64_t, 4> corner{};
    for (int end = 0; end < 2; ++end)
    {
      std::array<std::int64_t, 3> g = c;
      g[axis] += 1;
      g[u] += square[edge + end][0];
      g[v] += square[edge + end][1];
      corner[end] = this->CornerId(g[0], g[1], g[2]);
    }
    ids = { this->CentreId(cube), this->CentreId(neighbour), corner[0], corner[1] };
    return true;
  }
};

// A piece's frame: the cubes of the whole image's frame (anchored on its tissue box, as below)
// that cover the piece's part of that box.
bool MakePieceFrame(const LabelImage& image, double h, LatticeFrame& frame)
{
  frame.H = h;
  for (int a = 0; a < 3; ++a)
  {
    const int lower = std::max(image.LatticeBoxLower[a], 0);
    const int upper = std::min(image.LatticeBoxUpper[a], image.Dimensions[a] - 1);
    if (lower > upper)
    {
      return false;
    }
    const double anchor = image.Spacing[a] * image.LatticeBoxLower[a] - h;
    const double lo = image.Spacing[a] * lower;
    const double hi = image.Spacing[a] * upper;
    const std::int64_t skipped = static_cast<std::int64_t>(std::floor((lo - anchor) / h)) - 1;
    frame.CornerOrigin[a] = anchor + double(skipped) * h;
    frame.Cubes[a] = static_cast<std::int64_t>(std::floor((hi - anchor) / h)) + 2 - skipped;
  }
  return true;
}

bool MakeFrame(const LabelImage& image, double h, LatticeFrame& frame)
{
  if (image.HasLatticeBox)
  {
    return MakePieceFrame(image, h, frame);
  }
  std::array<int, 3> lower, upper;
  if (!TissueIndexBounds(image, lower, upper))
  {
    return false;
  }
  frame.H = h;
  for (int a = 0; a < 3; ++a)
  {
    const double lo = image.Spacing[a] * lower[a];
    const double hi = image.Spacing[a] * upper[a];
    // One cube of margin on each side puts the outermost cube centres beyond the tissue box,
    // so the tets between centres cover every tissue voxel centre.
    frame.CornerOrigin[a] = lo - h;
    frame.Cubes[a] = static_cast<std::int64_t>(std::floor((hi - lo) / h)) + 3;
  }
  return true;
}

std::string FormatBytes(double bytes)
{
  std::ostringstream out;
  out << std::setprecision(3) << bytes / (1024.0 * 1024.0 * 1024.0) << " GiB";
  return out.str();
}
} // namespace

double DefaultLatticeEdgeLength(const LabelImage& image)
{
  return DefaultLatticeEdgeLength(image.Spacing);
}

double DefaultLatticeEdgeLength(const Eigen::Vector3d& spacing)
{
  return 8.0 * spacing.minCoeff();
}

double BudgetLatticeEdgeLength(const LabelImage& image, std::int64_t maximumTets)
{
  std::int64_t tissueVoxels = 0;
  for (const std::int32_t label : image.Labels)
    tissueVoxels += image.IsTissue(label);
  const double volume = double(tissueVoxels) * image.Spacing.prod();
  return std::cbrt(4.0 * 12.0 * volume / double(std::max<std::int64_t>(1, maximumTets)));
}

double LatticeEdgeLengthFor(const LabelImage& image, const LatticeParams& params)
{
  const double automatic = DefaultLatticeEdgeLength(image);
  // The automatic size given as a number (as the ParaView panel shows it) counts as automatic.
  if (params.EdgeLength != 0.0 && std::abs(params.EdgeLength - automatic) > 1e-9 * automatic)
  {
    return params.EdgeLength;
  }
  if (params.MaximumTets <= 0)
  {
    return automatic;
  }
  return std::max(automatic, std::min(BudgetLatticeEdgeLength(image, params.MaximumTets), MaximumLatticeEdgeLength(image)));
}

double MaximumLatticeEdgeLength(const LabelImage& image)
{
  double widest = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    widest = std::max(widest, image.Dimensions[a] * image.Spacing[a]);
  }
  return widest;
}

double EstimateLatticeBytes(const LabelImage& image, double edgeLength)
{
  std::array<int, 3> lower, upper;
  if (!TissueIndexBounds(image, lower, upper) || !(edgeLength > 0.0))
  {
    return 0.0;
  }
  double cubes = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    cubes *= std::floor(image.Spacing[a] * (upper[a] - lower[a]) / edgeLength) + 3.0;
  }
  return cubes * BytesPerCube;
}

namespace
{
// The edge length to use (h), or an error: not positive, larger than the image, or a lattice
// that would not fit in the memory allowed.
Status ChooseLatticeEdge(const LabelImage& image, const LatticeParams& params, double& h)
{
  h = LatticeEdgeLengthFor(image, params);
  if (!(h > 0.0) || !std::isfinite(h))
  {
    return Status::Error("the lattice edge length must be a positive number of millimetres");
  }
  // (The default, 8 voxels, is cheap even over an image smaller than that, and is kept, also
  // when given explicitly, as the ParaView panel gives it.)
  if (params.EdgeLength != 0.0 &&
    h > std::max(MaximumLatticeEdgeLength(image), DefaultLatticeEdgeLength(image)))
  {
    std::ostringstream msg;
    msg << "a lattice size of " << h << " mm is larger than the image (" << MaximumLatticeEdgeLength(image)
        << " mm across its widest axis): it would give a handful of tetrahedra; choose at most that";
    return Status::Error(msg.str());
  }
  const std::size_t limit =
    params.MemoryLimitBytes > 0 ? params.MemoryLimitBytes : PhysicalMemoryBytes() / 2;
  const double needed = EstimateLatticeBytes(image, h);
  if (limit > 0 && needed > double(limit))
  {
    std::ostringstream msg;
    msg << "a lattice of edge " << h << " mm over this image would need "
        << (needed < 1e18 ? "about " + FormatBytes(needed) : std::string("more than an exabyte"))
        << " of memory, more than the " << FormatBytes(double(limit))
        << " allowed; choose a larger lattice size";
    return Status::Error(msg.str());
  }
  return Status::Ok();
}

// Every candidate tet (12 slots per cube), sampled in parallel: each writes only its own slots,
// kept where a tissue is its majority. False when `progress` asked to stop.
bool SampleSlots(const LabelImage& image, const LatticeFrame& frame, int threads,
  const Progress& progress, std::vector<std::int32_t>& slotLabel, std::vector<std::uint8_t>& slotKept)
{
  const std::int64_t cubes = frame.CubeCount();
  slotLabel.assign(12 * cubes, 0);
  slotKept.assign(12 * cubes, 0);
  std::atomic<bool> stop(false);
  std::atomic<std::int64_t> done(0);
  RegionErrors errors; // out of memory in a thread: thrown again below, not std::terminate
  const std::int64_t stride = std::min<std::int64_t>(cubes / 100 + 1, 1000);
#pragma omp parallel num_threads(ThreadCount(threads))
  {
    LabelCounts counts;
    std::int64_t ownCubes = 0; // thread 0 reports after every `stride` cubes of its own
#pragma omp for schedule(dynamic, 64)
    for (std::int64_t cube = 0; cube < cubes; ++cube)
    {
      if (stop.load(std::memory_order_relaxed) || errors.Failed())
      {
        continue;
      }
      errors.Run([&]() {
        for (int slot = 0; slot < 12; ++slot)
        {
          std::array<std::int64_t, 4> ids;
          if (!frame.SlotTet(cube, slot / 4, slot % 4, ids))
          {
            continue;
          }
          std::array<Eigen::Vector3d, 4> corners;
          for (int v = 0; v < 4; ++v)
          {
            corners[v] = image.Origin + image.Direction * frame.Position(ids[v]);
          }
          SampleTetLabels(image, corners, counts);
          std::int32_t label = 0;
          if (counts.MajorityTissue(image, label))
          {
            slotKept[12 * cube + slot] = 1;
            slotLabel[12 * cube + slot] = label;
          }
        }
      });
      const std::int64_t finished = done.fetch_add(1, std::memory_order_relaxed) + 1;
      if (progress && ThreadId() == 0 && ++ownCubes % stride == 0 &&
        !progress(0.95 * double(finished) / double(cubes)))
      {
        stop.store(true, std::memory_order_relaxed);
      }
    }
  }
  errors.Rethrow();
  // Thread 0 may have had no turn to report (a busy machine); ask once more before going on.
  return !stop.load() && !(progress && !progress(0.95));
}

// The frame's vertex id at a position in the image-axis frame: -1 where no lattice vertex is.
std::int64_t VertexIdAt(const LatticeFrame& frame, const Eigen::Vector3d& position)
{
  const Eigen::Vector3d half = (position - frame.CornerOrigin) * (2.0 / frame.H);
  std::array<std::int64_t, 3> q;
  for (int a = 0; a < 3; ++a)
  {
    q[a] = std::llround(half[a]);
    if (std::abs(half[a] - double(q[a])) > 1e-3)
      return -1;
  }
  const std::int64_t parity = q[0] & 1;
  if ((q[1] & 1) != parity || (q[2] & 1) != parity)
    return -1;
  std::array<std::int64_t, 3> g;
  for (int a = 0; a < 3; ++a)
  {
    g[a] = (q[a] - parity) / 2;
    if (g[a] < 0 || g[a] > frame.Cubes[a] - parity)
      return -1;
  }
  return parity ? frame.CentreId(g[0] + frame.Cubes[0] * (g[1] + frame.Cubes[1] * g[2]))
                : frame.CornerId(g[0], g[1], g[2]);
}

// The slot (12 per cube) of a tet given by its frame vertex ids; -1 where it is none.
std::int64_t SlotOf(const LatticeFrame& frame, std::array<std::int64_t, 4> ids)
{
  std::sort(ids.begin(), ids.end()); // corners first, then the two centres
  const std::int64_t first = ids[2] - frame.CornerCount(), second = ids[3] - frame.CornerCount();
  if (ids[1] >= frame.CornerCount() || first < 0)
    return -1;
  const std::int64_t steps[3] = { 1, frame.Cubes[0], frame.Cubes[0] * frame.Cubes[1] };
  for (int axis = 0; axis < 3; ++axis)
    for (int edge = 0; edge < 4 && second - first == steps[axis]; ++edge)
    {
      std::array<std::int64_t, 4> slot;
      if (frame.SlotTet(first, axis, edge, slot))
      {
        std::sort(slot.begin(), slot.end());
        if (slot == ids)
          return 12 * first + 4 * axis + edge;
      }
    }
  return -1;
}

// Appends the tet of these frame vertex ids, positively oriented, and the points it needs that
// `pointOf` (frame id -> point, -1: none yet) does not have yet.
void AppendTet(const LabelImage& image, const LatticeFrame& frame, const std::array<std::int64_t, 4>& ids,
  std::int32_t label, std::vector<PointId>& pointOf, TetMesh& mesh)
{
  Tet tet;
  for (int v = 0; v < 4; ++v)
  {
    PointId& id = pointOf[ids[v]];
    if (id < 0)
    {
      CheckPointCount(mesh.Points.size() + 1);
      id = static_cast<PointId>(mesh.Points.size());
      mesh.Points.push_back(image.Origin + image.Direction * frame.Position(ids[v]));
    }
    tet[v] = id;
  }
  const auto& p = mesh.Points;
  if (SignedVolume(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]) < 0.0)
  {
    std::swap(tet[2], tet[3]);
  }
  mesh.Tets.push_back(tet);
  mesh.Labels.push_back(label);
}

// The kept slots as tets, serially and in slot order, so the numbering is the same for any
// thread count; each tet positively oriented.
void AssembleKeptSlots(const LabelImage& image, const LatticeFrame& frame,
  const std::vector<std::int32_t>& slotLabel, const std::vector<std::uint8_t>& slotKept, TetMesh& mesh)
{
  const std::int64_t cubes = frame.CubeCount();
  std::vector<PointId> pointOf(frame.CornerCount() + cubes, -1);
  for (std::int64_t slot = 0; slot < 12 * cubes; ++slot)
  {
    if (!slotKept[slot])
    {
      continue;
    }
    std::array<std::int64_t, 4> ids;
    frame.SlotTet(slot / 12, int(slot % 12) / 4, int(slot % 4), ids);
    AppendTet(image, frame, ids, slotLabel[slot], pointOf, mesh);
  }
}
} // namespace

Status BuildBCCLattice(const LabelImage& image, const LatticeParams& params, TetMesh& mesh,
  const Progress& progress)
{
  mesh = TetMesh();
  const Status valid = ValidateLabelImage(image);
  if (!valid.IsOk())
  {
    return valid;
  }
  double h = 0.0;
  const Status edge = ChooseLatticeEdge(image, params, h);
  if (!edge.IsOk())
  {
    return edge;
  }
  LatticeFrame frame;
  MakeFrame(image, h, frame);
  std::vector<std::int32_t> slotLabel;
  std::vector<std::uint8_t> slotKept;
  if (!SampleSlots(image, frame, params.NumberOfThreads, progress, slotLabel, slotKept))
  {
    return Status::Aborted();
  }
  AssembleKeptSlots(image, frame, slotLabel, slotKept, mesh);
  if (progress)
  {
    progress(1.0);
  }
  return Status::Ok();
}

bool AddBackgroundRing(const LabelImage& image, TetMesh& lattice)
{
  if (lattice.Tets.empty() || image.BackgroundLabels.empty())
    return false;
  // The lattice's cube edge is its tets' longest edge; the frame follows from it and the image.
  double h = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b)
      h = std::max(h, (lattice.Points[lattice.Tets[0][a]] - lattice.Points[lattice.Tets[0][b]]).norm());
  LatticeFrame frame;
  if (!MakeFrame(image, h, frame))
    return false;
  // One cube more on every side: a lattice tet may have a vertex on its frame's boundary.
  frame.CornerOrigin -= Eigen::Vector3d::Constant(h);
  for (std::int64_t& cubes : frame.Cubes)
    cubes += 2;
  const Eigen::Matrix3d toFrame = image.Direction.inverse();
  std::vector<std::int64_t> idOfPoint(lattice.Points.size());
  std::vector<PointId> pointOf(frame.CornerCount() + frame.CubeCount(), -1);
  for (std::size_t p = 0; p < lattice.Points.size(); ++p)
  {
    idOfPoint[p] = VertexIdAt(frame, toFrame * (lattice.Points[p] - image.Origin));
    if (idOfPoint[p] < 0)
      return false; // not this image's lattice
    pointOf[idOfPoint[p]] = static_cast<PointId>(p);
  }
  std::vector<char> present(12 * frame.CubeCount(), 0);
  for (const Tet& tet : lattice.Tets)
  {
    const std::int64_t slot =
      SlotOf(frame, { idOfPoint[tet[0]], idOfPoint[tet[1]], idOfPoint[tet[2]], idOfPoint[tet[3]] });
    if (slot < 0)
      return false;
    present[slot] = 1;
  }
  const std::int32_t background = image.BackgroundLabels.front();
  for (std::int64_t slot = 0; slot < std::int64_t(present.size()); ++slot)
  {
    std::array<std::int64_t, 4> ids;
    if (present[slot] || !frame.SlotTet(slot / 12, int(slot % 12) / 4, int(slot % 4), ids) ||
      std::none_of(ids.begin(), ids.end(), [&](std::int64_t id) { return pointOf[id] >= 0 && pointOf[id] < PointId(idOfPoint.size()); }))
      continue;
    AppendTet(image, frame, ids, background, pointOf, lattice);
  }
  return true;
}
} // namespace cbc3d
