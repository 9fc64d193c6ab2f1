#ifndef cbc3d_SurfaceEars_h
#define cbc3d_SurfaceEars_h

#include "cbc3d/base/TetMesh.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace cbc3d
{
/// Ears: tissue tets with a vertex that no other tissue tet uses. Such a tet is a spike on
/// the surface: deformation cannot bring its tip onto the image boundary without flattening
/// it, so the tip stays off the boundary. Each ear whose base (the face opposite the tip) is
/// shared with a tet of its own label is given `removed` (so its tissue keeps the tets it is
/// attached to); the search repeats until no such ear is left. `isTissue` tells tissue labels;
/// `across` is FaceNeighbours(tets). Returns how many tets it relabelled.
std::size_t RemoveSurfaceEars(const std::vector<Tet>& tets,
  const std::vector<TetNeighbours>& across, std::size_t pointCount,
  std::vector<std::int32_t>& labels, const std::function<bool(std::int32_t)>& isTissue,
  std::int32_t removed);
} // namespace cbc3d

#endif
