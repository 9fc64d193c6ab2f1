#ifndef cbc3d_BCCLattice_h
#define cbc3d_BCCLattice_h

// Stage: the lattice. Takes a label image and a lattice size; gives the BCC lattice's tets over
// the image (this file) and the red-green mesh (RedGreenMesh.h), the hierarchy that refinement
// splits and closes so that the mesh stays conforming.

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/Progress.h"
#include "cbc3d/base/Status.h"
#include "cbc3d/base/TetMesh.h"

#include <cstdint>

namespace cbc3d
{
struct LatticeParams
{
  /// Edge of the lattice cube in mm (the paper's BCC_size); 0 = DefaultLatticeEdgeLength.
  double EdgeLength = 0.0;
  /// With the automatic edge length: a tet budget (0 = none). The edge grows past the
  /// automatic one where the lattice would hold more than a quarter of it (BudgetLatticeEdgeLength),
  /// leaving refinement the rest.
  std::int64_t MaximumTets = 0;
  /// OpenMP threads; 0 = all cores.
  int NumberOfThreads = 0;
  /// Refuse a lattice whose estimated memory exceeds this (bytes); 0 = half the machine.
  std::size_t MemoryLimitBytes = 0;
};

/// The paper's choice of 8 voxel spacings, measured along the finest image axis.
double DefaultLatticeEdgeLength(const LabelImage& image);
/// The same from the voxel spacing alone (all that a pipeline knows before it reads voxels).
double DefaultLatticeEdgeLength(const Eigen::Vector3d& spacing);

/// The shortest edge length whose lattice holds about a quarter of `maximumTets` tets: a BCC
/// lattice has 12 tets per cube, so 12 V / h^3 over the tissues' volume V.
double BudgetLatticeEdgeLength(const LabelImage& image, std::int64_t maximumTets);

/// The edge length BuildBCCLattice uses: params.EdgeLength, or where that is 0 (or the
/// automatic size itself, as a panel shows it) the automatic one, grown for a tet budget.
double LatticeEdgeLengthFor(const LabelImage& image, const LatticeParams& params);

/// The largest useful edge length: the image's extent along its widest axis. A larger cube
/// than the whole image gives a handful of tets, and sampling them costs time in proportion to
/// their volume, so BuildBCCLattice refuses it when given explicitly, unless it is no larger
/// than the default (kept, as cheap, over an image narrower than 8 voxels).
double MaximumLatticeEdgeLength(const LabelImage& image);

/// Estimated peak memory of BuildBCCLattice for this edge length, in bytes.
double EstimateLatticeBytes(const LabelImage& image, double edgeLength);

/// Fills the tissues' bounding box with a body-centred cubic lattice aligned with the image
/// axes: the vertices are the cube corners and cube centres, and every pair of face-adjacent
/// cube centres carries four tets (two edges of length h and four of length h*sqrt(3)/2, so
/// four 60 degree and two 90 degree dihedral angles). Tets that hold no tissue sample are
/// dropped; each kept tet takes its majority tissue label. The mesh is in world coordinates,
/// every tet positively oriented even when the image direction is a reflection. Every tissue
/// voxel centre lies in (or on the boundary of) some kept tet.
Status BuildBCCLattice(const LabelImage& image, const LatticeParams& params, TetMesh& mesh,
  const Progress& progress = nullptr);

/// Adds to a lattice that BuildBCCLattice made for `image` every lattice tet that shares a vertex
/// with one of its tets, labelled with the image's first background label: a ring of background
/// round the tissues, where refinement's sound labelling can thicken a sheet of tissue one tet
/// thick rather than punch it (without it the mesh ends where the tissue does, on both sides of
/// the sheet). Returns false, the mesh unchanged, where the mesh is not such a lattice.
bool AddBackgroundRing(const LabelImage& image, TetMesh& lattice);
} // namespace cbc3d

#endif
