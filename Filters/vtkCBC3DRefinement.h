/**
 * @class   vtkCBC3DRefinement
 * @brief   Red-green refinement of a tet mesh driven by the voxel fidelity of every tissue.
 *
 * The second stage of the CBC3D method (Drakopoulos et al., IMR 2014, section 3.2). Input port
 * 0: a tetrahedral mesh, normally the output of vtkCBC3DBCCLattice; input port 1: the label
 * image (its label array is input array 0; background labels as in the other filters).
 *
 * Each pass labels every tet with the majority label of the voxel centres it holds (a tet that
 * holds none is sampled on a finer sub-grid), measures for each tissue F1 = |S1 n S2| / |S1|
 * and F2 = |S1 n S2| / |S2| (S1: voxels in the tissue's tets, S2: the tissue's voxels), and
 * splits red (1:8, along the shortest inner diagonal, so BCC tets give half-size BCC tets) the
 * tets that cross the boundary of a tissue whose F1 or F2 is below Fidelity. It also splits where
 * the surface would leave the image boundary far from its vertices, the paper's Hausdorff
 * measure (BoundaryDistance). Green splits (one edge: 2 tets, two opposite edges: 4, three edges
 * of a face: 4; two edges of a face get the third split too) close the mesh; any other pattern
 * is split red, and a green tet is never split (its red parent is). Refinement ends when every
 * tissue reaches Fidelity and BoundaryDistance, or no tet may be split without making edges
 * shorter than MinimumEdgeLength. Every 6-connected tissue component of at least MinimumComponentVoxels
 * voxels keeps at least one tet of its tissue. Then (SoundLabels) tets are relabelled so that no
 * tet hangs on an edge or a vertex, every tissue surface and interface is a 2-manifold, and no
 * tissue or background piece stands for nothing in the image, nor does any cavity of the image
 * open to the outside. For that, when the input is this image's BCC lattice, refinement first adds
 * the lattice tets around it as background (a ring, one tet deep), so that a sheet of tissue one
 * tet thick can be thickened rather than punched. Tets labelled background are dropped.
 *
 * Output: the refined mesh, conforming, every tet positively oriented; cell data `Label`
 * (vtkIntArray) and `RefinementLevel` (vtkUnsignedCharArray: 0 for lattice tets, +1 per red
 * split); field data `RefinementPasses` (vtkIntArray), `RefinementStopReason` (vtkStringArray),
 * `RefinementBoundaryDistance` (the bound used, mm; 0 when none) and `RefinementBoundaryGap`
 * (the farthest boundary voxel from the predicted surface, mm) (vtkDoubleArray),
 * `RefinementRelabelledTets` (tets relabelled for sound labels) (vtkIdTypeArray),
 * and per tissue in ascending label order `FidelityLabel` (vtkIntArray), `FidelityF1`,
 * `FidelityF2` (vtkDoubleArray), `FidelityComponents`, `FidelityComponentsInMesh`
 * (vtkIdTypeArray).
 *
 * @sa vtkCBC3DBCCLattice vtkCBC3DMeshQuality
 */
#ifndef vtkCBC3DRefinement_h
#define vtkCBC3DRefinement_h

#include "vtkCBC3DAlgorithm.h"
#include "vtkCBC3DFiltersModule.h" // For export macro

#include <memory> // For SetRankPasses

namespace cbc3d
{
struct RankPasses;
}

class VTKCBC3DFILTERS_EXPORT vtkCBC3DRefinement : public vtkCBC3DAlgorithm
{
public:
  static vtkCBC3DRefinement* New();
  vtkTypeMacro(vtkCBC3DRefinement, vtkCBC3DAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Target fidelity F in [0, 1] for F1 and F2 of every tissue (default 0.95, the paper's).
   * 0 refines nothing: the tets are only relabelled by majority.
   */
  vtkSetMacro(Fidelity, double);
  vtkGetMacro(Fidelity, double);
  ///@}

  ///@{
  /**
   * No split makes edges shorter than this, in mm (the depth limit). 0 (the default) uses the
   * voxel size, the cube root of the voxel volume.
   */
  vtkSetMacro(MinimumEdgeLength, double);
  vtkGetMacro(MinimumEdgeLength, double);
  ///@}

  /**
   * Whether the settings ask for any refinement: a fidelity above 0 (for all tissues or one)
   * or an edge limit. The command line and the Mesher run this stage only then.
   */
  bool AsksForRefinement() const { return this->Fidelity > 0.0 || this->SizeControlsAskForRefinement(); }

  // The size controls of vtkCBC3DAlgorithm apply: SetTissueFidelity (targets of single
  // tissues), the edge limits (tets holding voxels of a tissue with a limit are refined to it
  // too, so that sizes grade away from the tissue; splits for a limit obey only a
  // MinimumEdgeLength that is set) and MaximumNumberOfTets.

  ///@{
  /**
   * Every boundary voxel of a tissue should end within this distance (mm) of a vertex of the
   * tissue's surface: where the surface after deformation (predicted: each surface vertex moved
   * to its nearest boundary voxel) would leave voxels farther, the longest edge of the nearest
   * surface face is split, and tets with a vertex that cannot reach the boundary are split red.
   * 0 (the default) = 3/8 of the input mesh's longest edge (3 mm for an 8 mm lattice);
   * negative = no such bound (voxel fidelity alone, as in the paper).
   */
  vtkSetMacro(BoundaryDistance, double);
  vtkGetMacro(BoundaryDistance, double);
  ///@}

  ///@{
  /**
   * The values that MinimumEdgeLength 0 and BoundaryDistance 0 stand for, as of the last
   * UpdateInformation: the ParaView panel fills them in. The first comes from the image's
   * spacing, the second from the edge of the vtkCBC3DBCCLattice that makes the mesh on port 0
   * (a BCC lattice's longest edges are its cube edges); each is 0 while unknown.
   */
  double GetAutomaticMinimumEdgeLength() const { return this->AutomaticMinimumEdge(); }
  double GetAutomaticBoundaryDistance() const;
  ///@}

  ///@{
  /**
   * Tissue components (6-connected) of at least this many voxels always keep tets of their
   * tissue (default 8).
   */
  vtkSetClampMacro(MinimumComponentVoxels, int, 1, VTK_INT_MAX);
  vtkGetMacro(MinimumComponentVoxels, int);
  ///@}

  ///@{
  /**
   * Relabel tets at the end so that the mesh is a sound finite-element model (default on): no
   * tet hangs on an edge or a vertex, every tissue surface and interface is a 2-manifold, and no
   * tissue has a piece (or a cavity) that the image lacks. Off leaves the majority labels, for
   * comparison.
   */
  vtkSetMacro(SoundLabels, bool);
  vtkGetMacro(SoundLabels, bool);
  vtkBooleanMacro(SoundLabels, bool);
  ///@}

#ifndef __VTK_WRAP__
  /// Over MPI ranks (vtkCBC3DMesher sets it): the decisions the ranks' passes share.
  void SetRankPasses(std::shared_ptr<const cbc3d::RankPasses> ranks) { this->Ranks = std::move(ranks); }
#endif

protected:
  vtkCBC3DRefinement();
  ~vtkCBC3DRefinement() override = default;

  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double InputLatticeEdge = 0.0; // from RequestInformation; 0: unknown
  double Fidelity = 0.95;
  double MinimumEdgeLength = 0.0;
  double BoundaryDistance = 0.0;
  int MinimumComponentVoxels = 8;
  bool SoundLabels = true;
#ifndef __VTK_WRAP__
  std::shared_ptr<const cbc3d::RankPasses> Ranks;
#endif

private:
  vtkCBC3DRefinement(const vtkCBC3DRefinement&) = delete;
  void operator=(const vtkCBC3DRefinement&) = delete;
};

#endif
