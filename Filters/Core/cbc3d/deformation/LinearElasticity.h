#ifndef cbc3d_LinearElasticity_h
#define cbc3d_LinearElasticity_h

#include "cbc3d/base/Progress.h"
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/deformation/BlockMatrix.h"

#include <cstdint>
#include <map>

namespace cbc3d
{
/// Isotropic linear-elastic material.
struct Material
{
  double YoungModulus = 1.0; // any unit: only ratios between tissues matter here
  double PoissonRatio = 0.3;
};

/// The stiffness matrix of linear elasticity on 4-node linear tets: 3 degrees of freedom per
/// point (x, y, z of point p at 3p..3p+2), K = sum over tets of V B^T D B. Each tet's material
/// is looked up by its label (`fallback` for labels not in `materials`). Assembled in parallel,
/// each block's sum in tet order, so the result does not depend on the thread count. Polls
/// `progress` (on the calling thread) between its steps; a stop returns an empty matrix.
BlockMatrix AssembleStiffness(const TetMesh& mesh,
  const std::map<std::int32_t, Material>& materials, const Material& fallback, int numberOfThreads = 0,
  const Progress& progress = nullptr);
} // namespace cbc3d

#endif
