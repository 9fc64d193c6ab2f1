#include "vtkCBC3DComponentJoin.h"

#include "cbc3d/base/DisjointSets.h"
#include "cbc3d/base/LabelImage.h"
#include "cbc3d/sampling/TissueComponents.h"

#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkTypeInt64Array.h>

#include <algorithm>
#include <cstdint>

namespace
{
constexpr std::int64_t NoComponent = -1;

// The components (numbered over all ranks: `offset` plus this rank's number) of the voxels of
// two slices, `slice` and the next (whole-image structured indices along plan.Axis), in the
// order of the other two axes; NoComponent where none.
void SliceComponents(const vtkCBC3DPieces::SlabPlan& plan, const int extent[6], const cbc3d::LabelImage& image,
  const cbc3d::RunComponents& components, std::int64_t offset, int slice, vtkTypeInt64Array* out)
{
  const int a = plan.Axis, b = (a + 1) % 3, c = (a + 2) % 3;
  for (int s = slice; s <= slice + 1; ++s)
    for (int v = extent[2 * c]; v <= extent[2 * c + 1]; ++v)
      for (int u = extent[2 * b]; u <= extent[2 * b + 1]; ++u)
      {
        std::int64_t component = NoComponent;
        if (!components.Runs.empty())
        {
          std::array<int, 3> at;
          at[a] = s - extent[2 * a];
          at[b] = u - extent[2 * b];
          at[c] = v - extent[2 * c];
          if (image.IsStored(at[0], at[1], at[2]))
          {
            const std::int32_t local = components.ComponentOf(image.VoxelIndex(at[0], at[1], at[2]));
            component = local < 0 ? NoComponent : offset + local;
          }
        }
        out->InsertNextValue(component);
      }
}

// Per component of the piece: its voxels in this rank's slab.
std::vector<std::int64_t> OwnSizes(const vtkCBC3DPieces::SlabPlan& plan, const int extent[6],
  const cbc3d::LabelImage& image, const cbc3d::RunComponents& components)
{
  const int a = plan.Axis;
  const int from = plan.Cuts[plan.Piece] - extent[2 * a], to = plan.Cuts[plan.Piece + 1] - extent[2 * a];
  std::vector<std::int64_t> sizes(components.Size.size(), 0);
  for (const cbc3d::RunComponents::Run& run : components.Runs)
  {
    const std::array<int, 3> first = image.VoxelCoordinates(run.First);
    const std::int64_t length = run.Last - run.First + 1;
    if (a != 0)
      sizes[run.Component] += first[a] >= from && first[a] < to ? length : 0;
    else
      sizes[run.Component] += std::max<std::int64_t>(0, std::min<std::int64_t>(to, first[0] + length) -
          std::max<std::int64_t>(from, first[0]));
  }
  return sizes;
}
} // namespace

namespace vtkCBC3DComponentJoin
{
void Join(vtkMultiProcessController* controller, const vtkCBC3DPieces::SlabPlan& plan, const int extent[6],
  const cbc3d::LabelImage& image, cbc3d::RunComponents& components, std::vector<char>* outside)
{
  const int ranks = controller->GetNumberOfProcesses(), me = controller->GetLocalProcessId();
  long long mine = static_cast<long long>(components.Size.size());
  std::vector<long long> counts(ranks, 0), offsets(ranks + 1, 0);
  controller->AllGather(&mine, counts.data(), 1);
  for (int r = 0; r < ranks; ++r)
    offsets[r + 1] = offsets[r] + counts[r];
  // Per component: its own voxels and whether it reaches the outside here; then the slices at
  // this rank's borders, as (border, side, components...).
  vtkNew<vtkTypeInt64Array> send, all;
  const std::vector<std::int64_t> sizes = OwnSizes(plan, extent, image, components);
  for (std::size_t c = 0; c < sizes.size(); ++c)
  {
    send->InsertNextValue(sizes[c]);
    send->InsertNextValue(outside ? (*outside)[c] : 0);
  }
  for (int border = std::max(1, plan.Piece); border <= std::min(plan.Piece + 1, plan.Pieces - 1); ++border)
  {
    send->InsertNextValue(border);
    send->InsertNextValue(border == plan.Piece ? 1 : 0); // 1: this rank lies above the border
    SliceComponents(plan, extent, image, components, offsets[me], plan.Cuts[border] - 1, send);
  }
  controller->AllGatherV(send, all);

  const std::int64_t total = offsets[ranks], theOutside = total;
  cbc3d::DisjointSets sets(std::size_t(total) + 1);
  std::vector<std::int64_t> ownSize(total);
  std::vector<char> reaches(total + 1, 0);
  reaches[theOutside] = 1;
  const int b = (plan.Axis + 1) % 3, c = (plan.Axis + 2) % 3; // the axes across the slabs
  const std::int64_t slices =
    2 * std::int64_t(extent[2 * b + 1] - extent[2 * b] + 1) * (extent[2 * c + 1] - extent[2 * c] + 1);
  std::vector<std::vector<std::int64_t>> below(plan.Pieces), above(plan.Pieces);
  vtkIdType at = 0;
  const int borders = plan.Pieces - 1;
  for (int r = 0; r < ranks; ++r)
  {
    for (long long c = 0; c < counts[r]; ++c, at += 2)
    {
      ownSize[offsets[r] + c] = all->GetValue(at);
      reaches[offsets[r] + c] = char(all->GetValue(at + 1));
    }
    const int mineBorders = (r > 0 ? 1 : 0) + (r + 1 < plan.Pieces ? 1 : 0);
    for (int k = 0; k < mineBorders && borders > 0; ++k)
    {
      const int border = int(all->GetValue(at));
      auto& side = all->GetValue(at + 1) ? above[border] : below[border];
      side.assign(all->GetPointer(at + 2), all->GetPointer(at + 2) + slices);
      at += 2 + slices;
    }
  }
  for (int border = 1; border < plan.Pieces; ++border)
    for (std::int64_t v = 0; v < slices; ++v)
    {
      const std::int64_t p = below[border][v], q = above[border][v];
      if (p >= 0 && q >= 0)
        sets.Join(p, q);
      else if (outside && (p >= 0 || q >= 0))
        sets.Join(std::max(p, q), theOutside); // the outside on the other side
    }
  std::vector<std::int64_t> wholeSize(total + 1, 0);
  std::vector<char> wholeReaches(total + 1, 0);
  for (std::int64_t c = 0; c <= total; ++c)
  {
    const std::int64_t root = sets.Find(c);
    wholeSize[root] += c < total ? ownSize[c] : 0;
    wholeReaches[root] = char(wholeReaches[root] | reaches[c]);
  }
  components.WholeId.resize(components.Size.size());
  for (std::size_t c = 0; c < components.Size.size(); ++c)
  {
    const std::int64_t root = sets.Find(offsets[me] + std::int64_t(c));
    components.WholeId[c] = root;
    components.Size[c] = wholeSize[root];
    if (outside)
      (*outside)[c] = wholeReaches[root];
  }
}
} // namespace vtkCBC3DComponentJoin
