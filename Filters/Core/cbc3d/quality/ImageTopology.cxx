#include "cbc3d/quality/ImageTopology.h"

#include "cbc3d/base/Parallel.h"

#include <algorithm>
#include <array>
#include <vector>

namespace cbc3d
{
namespace
{
// The index-space box (inclusive) of one tissue's voxels.
struct LabelBox
{
  std::int32_t Label;
  std::array<int, 3> Lower, Upper;
};

// Widens the box of piece.Label in `boxes` (added when new) to hold the piece.
void Widen(std::vector<LabelBox>& boxes, const LabelBox& piece)
{
  auto box = std::find_if(boxes.begin(), boxes.end(), [&](const LabelBox& b) { return b.Label == piece.Label; });
  if (box == boxes.end())
  {
    boxes.push_back(piece);
    return;
  }
  for (int a = 0; a < 3; ++a)
  {
    box->Lower[a] = std::min(box->Lower[a], piece.Lower[a]);
    box->Upper[a] = std::max(box->Upper[a], piece.Upper[a]);
  }
}

// Every tissue's box, run by run (LabelImage::ForEachRun: with the run index, a uniform stretch
// costs one step), slices on the threads; the threads' boxes are merged in thread order. Boxes
// are minima and maxima, so the same for any thread count; their order does not matter.
std::vector<LabelBox> TissueBoxes(const LabelImage& image, int threads)
{
  // The stored box holds every tissue voxel.
  const std::array<int, 3> first = image.StoredLower, upper = image.StoredUpper();
  const int count = ThreadCount(threads);
  std::vector<std::vector<LabelBox>> perThread(count);
  RegionErrors errors; // a new label's box may not find the memory
#pragma omp parallel for schedule(dynamic, 1) num_threads(count)
  for (int k = first[2]; k <= upper[2]; ++k)
  {
    std::vector<LabelBox>& boxes = perThread[ThreadId()];
    for (int j = first[1]; j <= upper[1] && !errors.Failed(); ++j)
      errors.Run([&] {
        image.ForEachRun(j, k, first[0], upper[0], [&](std::int32_t label, int voxels, int x) {
          if (!image.IsBackground(label))
            Widen(boxes, LabelBox{ label, { x, j, k }, { x + voxels - 1, j, k } });
        });
      });
  }
  errors.Rethrow();
  std::vector<LabelBox> boxes;
  for (const std::vector<LabelBox>& some : perThread)
    for (const LabelBox& box : some)
      Widen(boxes, box);
  return boxes;
}

// Around each voxel corner of one slice k: the 4 voxels of the slice that share the corner's
// edge along z, as bits (1: x - 1, y - 1; 2: x, y - 1; 4: x - 1, y; 8: x, y), set where
// `inside`. The corners run from lower to upper + 1 along x and y; voxels beyond the box are
// outside, and a slice beyond it is all zeros.
class CornerCodes
{
public:
  CornerCodes(const std::array<int, 3>& lower, const std::array<int, 3>& upper)
    : Lower(lower)
    , Upper(upper)
    , Width(upper[0] - lower[0] + 2)
    , Height(upper[1] - lower[1] + 2)
    , Voxels(std::size_t(Width + 1) * std::size_t(Height + 1))
    , Codes(std::size_t(Width) * std::size_t(Height))
  {
  }

  template <typename Inside>
  const std::vector<unsigned char>& Of(const LabelImage& image, int k, Inside inside)
  {
    std::fill(this->Voxels.begin(), this->Voxels.end(), 0);
    const int row = this->Width + 1;
    if (k >= this->Lower[2] && k <= this->Upper[2])
      for (int j = this->Lower[1]; j <= this->Upper[1]; ++j)
      {
        const std::int64_t first = image.VoxelIndex(this->Lower[0], j, k);
        unsigned char* out = this->Voxels.data() + std::size_t(j - this->Lower[1] + 1) * row + 1;
        for (int i = 0; i + this->Lower[0] <= this->Upper[0]; ++i)
          out[i] = inside(first + i) ? 1 : 0;
      }
    for (int j = 0; j < this->Height; ++j)
    {
      const unsigned char* below = this->Voxels.data() + std::size_t(j) * row;
      const unsigned char* above = below + row;
      unsigned char* code = this->Codes.data() + std::size_t(j) * this->Width;
      for (int i = 0; i < this->Width; ++i)
        code[i] = below[i] | below[i + 1] << 1 | above[i] << 2 | above[i + 1] << 3;
    }
    return this->Codes;
  }

private:
  std::array<int, 3> Lower, Upper;
  int Width, Height;                 // corners per row, rows
  std::vector<unsigned char> Voxels; // the slice, one voxel of zeros around it
  std::vector<unsigned char> Codes;
};

// Whether the voxels of these bits (of a corner code) are neither all inside nor all outside.
inline bool Mixed(unsigned bits, unsigned all)
{
  return bits != 0 && bits != all;
}

// Two sums over the corners of a box: V - E + F of the voxel-face surface, and V - E + F - C of
// the voxels joined through faces only (vertices at voxel centres, edges between face neighbours,
// squares and cubes where 4 and 8 voxels are all inside).
struct EulerSums
{
  std::int64_t Face = 0;
  std::int64_t Parted = 0;
  EulerSums& operator+=(const EulerSums& other)
  {
    this->Face += other.Face;
    this->Parted += other.Parted;
    return *this;
  }
};

// Whether all the voxels of these bits (of a corner code) are inside.
inline bool All(unsigned bits, unsigned all)
{
  return bits == all;
}

// The sums of the corners k in [first, last] of the box. Voxel-face: a corner, edge or face is
// on the surface when its voxels (8, 4 or 2) are mixed; each corner counts itself, its edges
// towards +x, +y and +z and its faces whose lowest corner it is, all among its 8 voxels, so a
// corner with none mixed counts nothing. Parted: each corner counts the cells whose highest
// voxel is its voxel (x, y, k): that voxel, its pairs with the voxels below it along x, y and
// z, its three squares and the cube of the corner's 8 voxels.
template <typename Inside>
EulerSums SlabEuler(const LabelImage& image, const std::array<int, 3>& lower, const std::array<int, 3>& upper,
  int first, int last, Inside inside)
{
  std::array<CornerCodes, 2> slices = { CornerCodes(lower, upper), CornerCodes(lower, upper) };
  const std::vector<unsigned char>* below = &slices[0].Of(image, first - 1, inside);
  EulerSums sums;
  for (int k = first; k <= last; ++k)
  {
    const std::vector<unsigned char>& previous = *below;
    const std::vector<unsigned char>& current = slices[(k - first + 1) % 2].Of(image, k, inside);
    for (std::size_t c = 0; c < current.size(); ++c)
    {
      const unsigned q0 = previous[c], q1 = current[c];
      if ((q0 | q1 << 4) == 0 || (q0 | q1 << 4) == 255)
        continue;
      const unsigned edgeX = (q0 >> 1 & 1) | (q0 >> 3 & 1) << 1 | (q1 >> 1 & 1) << 2 | (q1 >> 3 & 1) << 3;
      const unsigned edgeY = (q0 >> 2) | (q1 >> 2) << 2;
      const unsigned pairX = q1 >> 2, pairY = (q1 >> 1 & 1) | (q1 >> 3 & 1) << 1, pairZ = (q0 >> 3) | (q1 >> 3) << 1;
      sums.Face += 1 - Mixed(edgeX, 15) - Mixed(edgeY, 15) - Mixed(q1, 15);
      sums.Face += Mixed(pairX, 3) + Mixed(pairY, 3) + Mixed(pairZ, 3);
      sums.Parted += int(q1 >> 3) - All(pairX, 3) - All(pairY, 3) - All(pairZ, 3);
      sums.Parted += All(q1, 15) + All(edgeX, 15) + All(edgeY, 15);
    }
    below = &current;
  }
  return sums;
}

// The sums for the voxels `inside(voxelIndex)` selects, all of them within [lower, upper]: slabs
// of corner slices on the threads, summed exactly (integers), so the same for any thread count;
// no memory beyond a few slices per thread.
template <typename Inside>
EulerSums VoxelSurfaceEuler(const LabelImage& image, const std::array<int, 3>& lower,
  const std::array<int, 3>& upper, int threads, Inside inside)
{
  const int slices = upper[2] - lower[2] + 2; // corner slices lower[2] .. upper[2] + 1
  const int slabs = std::min(slices, 8 * ThreadCount(threads));
  std::vector<EulerSums> perSlab(slabs);
  RegionErrors errors; // each slab keeps a few slices of corners
#pragma omp parallel for schedule(dynamic, 1) num_threads(ThreadCount(threads))
  for (int slab = 0; slab < slabs; ++slab)
  {
    const int first = lower[2] + int(std::int64_t(slices) * slab / slabs);
    const int last = lower[2] + int(std::int64_t(slices) * (slab + 1) / slabs) - 1;
    errors.Run([&] { perSlab[slab] = SlabEuler(image, lower, upper, first, last, inside); });
  }
  errors.Rethrow();
  EulerSums sums;
  for (const EulerSums& slab : perSlab)
    sums += slab;
  return sums;
}

ImageTopology Measure(const LabelImage& image, bool withWhole, int numberOfThreads)
{
  ImageTopology topology;
  const std::vector<LabelBox> boxes = TissueBoxes(image, numberOfThreads);
  if (boxes.empty())
  {
    return topology;
  }
  LabelBox whole = boxes[0];
  for (const LabelBox& box : boxes)
  {
    for (int a = 0; a < 3; ++a)
    {
      whole.Lower[a] = std::min(whole.Lower[a], box.Lower[a]);
      whole.Upper[a] = std::max(whole.Upper[a], box.Upper[a]);
    }
  }
  // One tissue after another, each in parallel; the whole body is the tissue where there is one.
  const auto& labels = image.Labels;
  std::vector<EulerSums> sums;
  for (const LabelBox& box : boxes)
  {
    sums.push_back(VoxelSurfaceEuler(image, box.Lower, box.Upper, numberOfThreads,
      [&labels, &box](std::int64_t v) { return labels[v] == box.Label; }));
  }
  if (withWhole)
  {
    sums.push_back(boxes.size() == 1 ? sums[0]
                                     : VoxelSurfaceEuler(image, whole.Lower, whole.Upper, numberOfThreads,
                                         [&image](std::int64_t v) { return image.IsTissue(image.Labels[v]); }));
  }
  // The joined reading follows from these two (ImageTopology::PinchesJoined).
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    topology.TissueSurfaceEuler[boxes[i].Label] = sums[i].Face;
    topology.TissuePinchesPartedEuler[boxes[i].Label] = 2 * sums[i].Parted;
  }
  if (withWhole)
  {
    topology.WholeSurfaceEuler = sums.back().Face;
    topology.WholePinchesPartedEuler = 2 * sums.back().Parted;
  }
  return topology;
}
} // namespace

ImageTopology MeasureImageTopology(const LabelImage& image, int numberOfThreads)
{
  return Measure(image, true, numberOfThreads);
}

std::map<std::int32_t, std::int64_t> ImageSurfaceEuler(const LabelImage& image, int numberOfThreads)
{
  return Measure(image, false, numberOfThreads).TissueSurfaceEuler;
}
} // namespace cbc3d
