/**
 * @class   vtkCBC3DMesher
 * @brief   Label image in, final CBC3D mesh out: lattice, refinement, deformation and quality.
 *
 * Runs vtkCBC3DBCCLattice, vtkCBC3DRefinement (when a fidelity or an edge limit asks for it), vtkCBC3DDeformation (when
 * Iterations > 0) and vtkCBC3DMeshQuality (with the image) in one go, reporting progress per
 * stage (with the stage's name as progress text) and stopping within a stage's next progress
 * report when aborted, with an empty output. The output holds every array of the stages:
 * `Label`, `RefinementLevel`, `MinDihedralAngle`, `MaxDihedralAngle` per tet, `Displacement`
 * per point, and the stages' field data (see vtkCBC3DArrayNames.h).
 *
 * Under MPI (`mpiexec -n N pvbatch`, pvserver), where the pipeline asks for one piece per rank,
 * each rank asks upstream only for its slab of the image along the longest axis and a halo of
 * lattice cubes, meshes it on the lattice of the whole image (its refinement passes taking the
 * decisions of the whole image: cbc3d::RankPasses), and keeps the tets whose centres lie in its
 * slab; points on rank borders take their owner's position, and the ranks check that
 * their border faces match (vtkCBC3DSeams). Deformation then runs on the ranks' own tets, each
 * point moved by one rank that holds every tet around it (vtkCBC3DRankDeformation). The pieces
 * carry `GlobalIds`, so writers merge them (vtkCBC3DMeshWriter writes one file). A tet budget
 * (MaximumNumberOfTets) is refused over ranks, with one error on the first rank.
 *
 * @sa vtkCBC3DBCCLattice vtkCBC3DRefinement vtkCBC3DDeformation vtkCBC3DMeshQuality
 */
#ifndef vtkCBC3DMesher_h
#define vtkCBC3DMesher_h

#include "vtkCBC3DAlgorithm.h"
#include "vtkCBC3DFiltersModule.h" // For export macro

#include <vtkSmartPointer.h> // For KeepOwnTets

#include <string> // For RunStage
#include <vector> // For SlabWeights

class vtkImageData;
class vtkUnstructuredGrid;

class VTKCBC3DFILTERS_EXPORT vtkCBC3DMesher : public vtkCBC3DAlgorithm
{
public:
  static vtkCBC3DMesher* New();
  vtkTypeMacro(vtkCBC3DMesher, vtkCBC3DAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Lattice cube edge in mm; 0 (the default) picks 8 times the finest voxel spacing.
   */
  vtkSetMacro(EdgeLength, double);
  vtkGetMacro(EdgeLength, double);
  ///@}

  ///@{
  /**
   * Fidelity target F for refinement (default 0.95; 0 skips refinement).
   */
  vtkSetMacro(Fidelity, double);
  vtkGetMacro(Fidelity, double);
  ///@}

  ///@{
  /**
   * Refinement makes no edge shorter than this, in mm (default 0: the voxel size). The edge
   * limits (MaximumEdgeLength, SetTissueMaximumEdgeLength: vtkCBC3DAlgorithm) go to
   * refinement, which splits until every tissue tet keeps them, and to deformation, which
   * stretches no edge past them.
   */
  vtkSetMacro(MinimumEdgeLength, double);
  vtkGetMacro(MinimumEdgeLength, double);
  ///@}


  ///@{
  /**
   * Refinement's bound on the distance from boundary voxels to the surface's vertices, in mm
   * (default 0: 3/8 of the lattice edge; negative: none; see vtkCBC3DRefinement).
   */
  vtkSetMacro(BoundaryDistance, double);
  vtkGetMacro(BoundaryDistance, double);
  ///@}

  ///@{
  /**
   * The values that EdgeLength, MinimumEdgeLength and BoundaryDistance 0 stand for, from the
   * image's spacing as of the last UpdateInformation (0 while unknown): the ParaView panel
   * fills them in. The boundary distance follows EdgeLength where that is set.
   */
  double GetAutomaticEdgeLength() const { return this->AutomaticLatticeEdge(); }
  double GetAutomaticMinimumEdgeLength() const { return this->AutomaticMinimumEdge(); }
  double GetAutomaticBoundaryDistance() const;
  ///@}

  ///@{
  /**
   * Deformation iterations (default 5; 0 skips deformation) and target pattern (0 Vertex,
   * 1 Edge (default), 2 Face, 3 None; see vtkCBC3DDeformation).
   */
  vtkSetClampMacro(Iterations, int, 0, 1000);
  vtkGetMacro(Iterations, int);
  vtkSetClampMacro(Pattern, int, 0, 3);
  vtkGetMacro(Pattern, int);
  ///@}

  ///@{
  /**
   * Deformation targets at boundary voxel centres (0) or on the label boundary (1, default);
   * see vtkCBC3DDeformation::TargetPlacement.
   */
  vtkSetClampMacro(TargetPlacement, int, 0, 1);
  vtkGetMacro(TargetPlacement, int);
  ///@}

  ///@{
  /**
   * Whether deformation ends by bringing each tissue to its voxels' volume (default on); see
   * vtkCBC3DDeformation::KeepVolumes.
   */
  vtkSetMacro(KeepVolumes, bool);
  vtkGetMacro(KeepVolumes, bool);
  vtkBooleanMacro(KeepVolumes, bool);
  ///@}

  ///@{
  /**
   * Over MPI ranks: the lattice cubes each rank meshes beyond its slab on each side (default 4).
   * The ranks' refinement passes share their decisions (each tissue's fidelity and the boundary
   * distance, summed over the slabs), but each rank splits and closes its own piece: the halo
   * keeps the piece's false border, where the image ends for the rank, away from its slab.
   * Where it is too thin, the ranks' border faces differ and the mesher says so. A wider halo
   * costs each rank memory and time in proportion.
   */
  vtkSetClampMacro(RankHalo, double, 1.0, 1000.0);
  vtkGetMacro(RankHalo, double);
  ///@}

  ///@{
  /**
   * Over MPI ranks: whether the slabs share the tissue's boundaries evenly rather than the
   * image's slices (default off: even slices). The tets gather at the boundaries, so this evens
   * out the ranks' tets, memory and time: on the 1 mm New York Head the largest of 3 slabs holds
   * 36% of the tets this way, 54% with even slices and 50% with even tissue voxels. The boundary
   * voxels per slice come from vtkCBC3DNIfTIReader (BOUNDARY_PER_SLICE), upstream of the mesher;
   * from other readers the slabs stay even. No slab is thinner than 6 lattice cubes. Off by
   * default: the deformation over ranks holds the points on the cuts in its first run, and where
   * a cut falls decides which tissue's maximum Hausdorff distance that costs (Documentation:
   * Meshing on a cluster).
   */
  vtkSetMacro(BalanceTissue, bool);
  vtkGetMacro(BalanceTissue, bool);
  vtkBooleanMacro(BalanceTissue, bool);
  ///@}

protected:
  vtkCBC3DMesher() = default;
  ~vtkCBC3DMesher() override = default;

  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double EdgeLength = 0.0;
  double Fidelity = 0.95;
  double BoundaryDistance = 0.0;
  double MinimumEdgeLength = 0.0;
  int Iterations = 5;
  int Pattern = 1;
  int TargetPlacement = 1; // vtkCBC3DDeformation::VOXEL_FACE
  bool KeepVolumes = true;
  double RankHalo = 4.0;
  bool BalanceTissue = false;

private:
  struct Piece;
  bool PreparePiece(vtkImageData* image, vtkInformation* inputInfo, Piece& piece);
  // The weight of each slice in cutting the slabs: its boundary voxels with BalanceTissue, else
  // none.
  std::vector<double> SlabWeights(vtkInformation* inputInfo) const;
  bool RunStages(vtkImageData* image, Piece* piece, vtkUnstructuredGrid* output);
  bool FinishStage(const char* name, const std::string& error, Piece* piece);
  // The stage filters' settings from the mesher's.
  void ConfigureStages(class vtkCBC3DBCCLattice* lattice, class vtkCBC3DRefinement* refinement,
    class vtkCBC3DDeformation* deformation) const;
  void PrepareStage(vtkCBC3DAlgorithm* filter, const char* arrayName, bool imageOnPort1) const;
  std::string RunStage(vtkAlgorithm* filter, const char* name, double shift, double scale);
  bool NamePiecePoints(vtkImageData* image, vtkAlgorithm* lattice, vtkUnstructuredGrid* mesh, Piece* piece);
  bool KeepOwnTets(vtkSmartPointer<vtkUnstructuredGrid>& mesh, Piece* piece);
  std::string DeformPiece(vtkUnstructuredGrid* mesh, vtkImageData* image, class vtkCBC3DDeformation* deformation,
    Piece* piece, double shift, double scale);

  vtkCBC3DMesher(const vtkCBC3DMesher&) = delete;
  void operator=(const vtkCBC3DMesher&) = delete;
};

#endif
