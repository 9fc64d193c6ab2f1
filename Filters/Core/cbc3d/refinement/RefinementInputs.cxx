#include "cbc3d/refinement/RefinementInputs.h"

#include "cbc3d/refinement/EdgeLimits.h"

#include <cmath>
#include <map>
#include <set>
#include <string>

namespace cbc3d
{
// The image, the mesh to refine and the parameters' ranges, or an error naming what is wrong.
Status ValidateInputs(const LabelImage& image, const TetMesh& lattice, const RefinementParams& params)
{
  const Status valid = ValidateLabelImage(image);
  if (!valid.IsOk())
  {
    return valid;
  }
  if (!(params.Fidelity >= 0.0 && params.Fidelity <= 1.0))
  {
    return Status::Error("the fidelity must be a number from 0 to 1");
  }
  for (const auto& [label, fidelity] : params.FidelityByTissue)
  {
    if (!image.IsTissue(label))
      return Status::Error("label " + std::to_string(label) + " is background, not a tissue: it has no fidelity");
    if (!(fidelity >= 0.0 && fidelity <= 1.0))
      return Status::Error("the fidelity of tissue " + std::to_string(label) + " must be a number from 0 to 1");
  }
  if (!(params.MaximumEdge.All >= 0.0) || !std::isfinite(params.MaximumEdge.All))
  {
    return Status::Error("the maximum edge length must be 0 (none) or a positive length in mm");
  }
  for (const auto& [label, length] : params.MaximumEdge.ByTissue)
  {
    if (!image.IsTissue(label))
      return Status::Error("label " + std::to_string(label) + " is background, not a tissue: it has no edge limit");
    if (!(length > 0.0) || !std::isfinite(length))
      return Status::Error("the maximum edge length of tissue " + std::to_string(label) + " must be a positive length in mm");
  }
  if (!(params.MinimumEdgeLength >= 0.0) || !std::isfinite(params.MinimumEdgeLength))
  {
    return Status::Error("the minimum edge length must be 0 (automatic) or a positive length in mm");
  }
  if (params.MaximumTets < 0)
  {
    return Status::Error("the tet budget must be 0 (none) or a positive number of tets");
  }
  if (!std::isfinite(params.BoundaryDistance))
  {
    return Status::Error("the boundary distance must be 0 (automatic), negative (none) or a "
                         "length in mm");
  }
  if (lattice.Tets.empty())
  {
    return Status::Error("the mesh to refine has no tets");
  }
  return CheckEdgeLimitsAboveFloor(params);
}

// A per-tissue target for a label with no voxel in the image is a mistake worth naming.
Status CheckTissuesPresent(const TissueComponents& components, const RefinementParams& params)
{
  std::set<std::int32_t> present(components.Label.begin(), components.Label.end());
  if (params.Ranks)
  {
    // A rank's piece may lack a tissue that another's holds.
    std::map<std::int64_t, double> labels;
    for (const std::int32_t label : present)
      labels[label] = 1.0;
    params.Ranks->SumByKey(labels);
    for (const auto& entry : labels)
      present.insert(std::int32_t(entry.first));
  }
  for (const auto* targets : { &params.FidelityByTissue, &params.MaximumEdge.ByTissue })
  {
    for (const auto& entry : *targets)
    {
      if (!present.count(entry.first))
        return Status::Error("the image has no voxel of tissue " + std::to_string(entry.first));
    }
  }
  return Status::Ok();
}
} // namespace cbc3d
