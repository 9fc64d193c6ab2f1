// Test of vtkCBC3DPieces::PlanSlabs, the slabs an image is cut into over MPI ranks, against
// answers known on paper:
// - without tissue counts, even shares of the slices;
// - tissue only in the upper half of the slices: 2 slabs cut at three quarters;
// - tissue growing linearly with the slice (weight s on slice s of n): 2 slabs cut where
//   c (c - 1) / 2 is half of n (n - 1) / 2, at c = n / sqrt(2) within a slice;
// - all tissue in one slice: no slab thinner than MinimumSlabCubes cubes;
// - the counts of the other axes (x, then y, then z in the list) are not mistaken for the
//   slabs' axis; a list of the wrong length is ignored.
#include "vtkCBC3DPieces.h"

#include "CBC3DTestUtilities.h"

#include <cmath>
#include <cstdlib>
#include <vector>

namespace
{
// An extent whose longest axis is z, n slices from `first`; x and y of 10 and 20 voxels.
struct Image
{
  explicit Image(int n, int first = 0)
    : Extent{ 0, 9, 0, 19, first, first + n - 1 }
  {
  }
  int Extent[6];
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  // Counts for x and y that would put every cut at their start if read as z's.
  std::vector<double> Counts(const std::vector<double>& alongZ) const
  {
    std::vector<double> counts(30, 0.0);
    counts[0] = counts[10] = 1e9;
    counts.insert(counts.end(), alongZ.begin(), alongZ.end());
    return counts;
  }
};

std::vector<int> Cuts(const Image& image, int pieces, const std::vector<double>& counts, double h = 1.0)
{
  const vtkCBC3DPieces::SlabPlan plan =
    vtkCBC3DPieces::PlanSlabs(image.Extent, image.Spacing, h, 4.0, pieces, 0, counts);
  CHECK(plan.Axis == 2);
  return plan.Cuts;
}
} // namespace

int TestCBC3DSlabPlan(int, char*[])
{
  const Image image(300, 5);
  CHECK((Cuts(image, 3, {}) == std::vector<int>{ 5, 105, 205, 305 }));
  CHECK((Cuts(image, 3, std::vector<double>(7, 1.0)) == std::vector<int>{ 5, 105, 205, 305 })); // wrong length

  std::vector<double> upperHalf(300, 0.0);
  for (int s = 150; s < 300; ++s)
  {
    upperHalf[s] = 4.0;
  }
  CHECK((Cuts(image, 2, image.Counts(upperHalf)) == std::vector<int>{ 5, 230, 305 }));

  const int n = 1000;
  const Image ramp(n);
  std::vector<double> growing(n);
  for (int s = 0; s < n; ++s)
  {
    growing[s] = s;
  }
  const std::vector<int> rampCuts = Cuts(ramp, 2, ramp.Counts(growing));
  CHECK(rampCuts.size() == 3 && std::abs(rampCuts[1] - n / std::sqrt(2.0)) <= 1.0);

  // All tissue in slice 0, cubes of 2 voxels: slabs of 12 slices at least.
  std::vector<double> oneSlice(300, 0.0);
  oneSlice[0] = 1.0;
  const std::vector<int> thin = Cuts(image, 3, image.Counts(oneSlice), 2.0);
  CHECK((thin == std::vector<int>{ 5, 17, 29, 305 }));
  // Where even shares are thinner than that, even shares.
  const Image few(30);
  std::vector<double> fewSlices(30, 0.0);
  fewSlices[29] = 1.0;
  CHECK((Cuts(few, 3, few.Counts(fewSlices), 2.0) == std::vector<int>{ 0, 10, 20, 30 }));
  return cbc3dtest::Finish();
}
