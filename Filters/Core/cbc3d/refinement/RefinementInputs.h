#ifndef cbc3d_RefinementInputs_h
#define cbc3d_RefinementInputs_h

#include "cbc3d/base/LabelImage.h"
#include "cbc3d/base/Status.h"
#include "cbc3d/base/TetMesh.h"
#include "cbc3d/refinement/Refinement.h"
#include "cbc3d/sampling/TissueComponents.h"

namespace cbc3d
{
/// The image, the mesh to refine and the parameters' ranges, or an error naming what is wrong.
Status ValidateInputs(const LabelImage& image, const TetMesh& lattice, const RefinementParams& params);

/// An error naming a tissue with a target of its own (a fidelity or an edge limit) that has no
/// voxel in the image.
Status CheckTissuesPresent(const TissueComponents& components, const RefinementParams& params);
} // namespace cbc3d

#endif
