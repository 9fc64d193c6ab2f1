/**
 * @file vtkCBC3DPieces.h
 * @brief How vtkCBC3DMesher splits an image over MPI ranks, and names lattice points (private).
 *
 * The image is cut into slabs along its longest axis, one per rank. A rank reads its slab and a
 * halo of lattice cubes on each side, meshes that piece on the lattice of the whole image, and
 * keeps the tets whose centres lie in its slab (vtkCBC3DSeams). The halo keeps the piece's
 * false borders (the image ends there for the rank) away from the tets it keeps.
 *
 * A lattice point's key packs its position in the whole image's lattice, in steps of 1/256 of
 * a cube edge, so every rank that holds a point gives it the same key without talking. (The
 * output's GlobalIds are compact numbers, 0 to the points less one: ParaView's data movement
 * keeps 32 bits of them.)
 */
#ifndef vtkCBC3DPieces_h
#define vtkCBC3DPieces_h

#include <vtkType.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkInformation;
class vtkMultiProcessController;
class vtkUnstructuredGrid;

namespace cbc3d
{
struct RankPasses;
}

namespace vtkCBC3DPieces
{
/// The slabs: piece r owns the structured indices [Cuts[r], Cuts[r + 1]) along Axis.
struct SlabPlan
{
  int Axis = 2;
  int Pieces = 1;
  int Piece = 0;
  std::vector<int> Cuts;
  int HaloVoxels = 0;
};

/// No slab is thinner than this many cubes (or than an even share of the slices, where that is
/// less): the deformation's bands (vtkCBC3DBandTets::ReachCubes) then reach no farther than the
/// next slab.
constexpr double MinimumSlabCubes = 6.0;

/// Splits the whole extent into `pieces` slabs along the longest physical axis; the halo is
/// `haloCubes` cubes of edge `h` (mm). The slabs hold an even share of the slices, or, given
/// `boundaryPerSlice` (the boundary voxels of each slice along x, then y, then z, as
/// vtkCBC3DNIfTIReader::BOUNDARY_PER_SLICE gives them), an even share of the boundaries, where
/// the tets gather.
SlabPlan PlanSlabs(const int wholeExtent[6], const double spacing[3], double h, double haloCubes, int pieces,
  int piece, const std::vector<double>& boundaryPerSlice = {});

/// The extent a piece reads: its slab and the halo, within the whole extent.
void PieceExtent(const SlabPlan& plan, const int wholeExtent[6], int extent[6]);

/// The box (structured indices, inclusive) of the image's tissue voxels: those that hold none of
/// the background values. False where the image holds none.
bool TissueBox(vtkImageData* image, vtkDataArray* labels, const std::vector<vtkTypeInt64>& background,
  int lower[3], int upper[3]);

/// The box of every rank's tissue; false where no rank has tissue.
bool AgreeOnTissueBox(vtkMultiProcessController* controller, bool has, const int lower[3],
  const int upper[3], int wholeLower[3], int wholeUpper[3]);

/// Whether every rank says yes (a collective: every rank calls it as often).
bool AllAgree(vtkMultiProcessController* controller, bool yes);

/// The boundary voxels of each slice where the reader counted them
/// (vtkCBC3DNIfTIReader::BOUNDARY_PER_SLICE, on the input or up a chain of one-input filters), so
/// that the slabs share the boundaries, and so the tets, rather than the slices. Empty where it
/// did not.
std::vector<double> BoundaryPerSlice(vtkInformation* inputInfo);

/// The ghost cells asked of a rank's piece (UPDATE_NUMBER_OF_GHOST_LEVELS on `outInfo`), in
/// VTK's way: vtkGhostCellsGenerator adds the neighbours' tets around the piece, joined by
/// GlobalIds and marked DUPLICATECELL in vtkGhostType, for the filters downstream that need
/// them. A collective call: every rank adds the most that any rank asks for. False on every
/// rank where that fails on one.
bool AddGhostCells(vtkMultiProcessController* controller, vtkInformation* outInfo, vtkUnstructuredGrid* output);

/// Where lattice points sit in the whole image's lattice.
struct LatticeKeys
{
  double Origin[3] = { 0, 0, 0 };          // the world position of structured index (0,0,0)
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  double Corner[3] = { 0, 0, 0 };          // the lattice's corner, mm along the image axes
  double Unit = 1.0;                       // one key step, mm

  /// For an image and its whole tissue box, and the lattice edge h.
  LatticeKeys(vtkImageData* image, const int wholeLower[3], double h);
  /// A point's key along each axis; false where it is off the key grid.
  bool Key(const double point[3], std::array<std::int64_t, 3>& key) const;
  /// The key of the plane between two voxel slices: before structured index `slice`.
  std::int64_t CutKey(int axis, int slice, double spacing) const;
};

/// The refinement decisions a rank shares with the others (its slab, and sums over the ranks
/// through `controller`), for the piece `image` of the plan.
std::shared_ptr<const cbc3d::RankPasses> MakeRankPasses(
  vtkMultiProcessController* controller, const SlabPlan& plan, vtkImageData* image);

/// One number per key (21 bits an axis), and back.
bool PackKey(const std::array<std::int64_t, 3>& key, vtkIdType& id);
std::array<std::int64_t, 3> UnpackKey(vtkIdType id);

/// The point array of packed keys, which vtkCBC3DSeams turns into compact GlobalIds.
constexpr const char* LatticeKeyName = "LatticeKey";

/// Adds the LatticeKey point array (packed keys) to a lattice mesh; false with a message where a
/// point is off the grid or beyond the range of the keys.
bool AddLatticeKeys(vtkUnstructuredGrid* mesh, const LatticeKeys& keys, std::string& error);
} // namespace vtkCBC3DPieces

#endif
