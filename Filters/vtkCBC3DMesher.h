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
 * @sa vtkCBC3DBCCLattice vtkCBC3DRefinement vtkCBC3DDeformation vtkCBC3DMeshQuality
 */
#ifndef vtkCBC3DMesher_h
#define vtkCBC3DMesher_h

#include "vtkCBC3DAlgorithm.h"
#include "vtkCBC3DFiltersModule.h" // For export macro

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

protected:
  vtkCBC3DMesher() = default;
  ~vtkCBC3DMesher() override = default;

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

private:
  vtkCBC3DMesher(const vtkCBC3DMesher&) = delete;
  void operator=(const vtkCBC3DMesher&) = delete;
};

#endif
