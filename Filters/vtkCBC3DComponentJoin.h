/**
 * @file vtkCBC3DComponentJoin.h
 * @brief Joins the components of the ranks' pieces of an image into the whole image's (private).
 *
 * Each rank labels the components of its piece (its slab and the halo). A component of the
 * whole image may fall apart in a piece, or run on into the next slab: the ranks join them where
 * they meet. Two neighbouring pieces both hold the two slices on either side of their slabs'
 * border, so a voxel there names a component on each side, and the two are one. The whole
 * component's size counts each rank's own slab.
 */
#ifndef vtkCBC3DComponentJoin_h
#define vtkCBC3DComponentJoin_h

#include "vtkCBC3DPieces.h"

#include <vector>

namespace cbc3d
{
struct LabelImage;
struct RunComponents;
}

namespace vtkCBC3DComponentJoin
{
/// A collective call: every rank gives its piece's components (`image` is the piece, of
/// structured extent `extent`; a rank without tissue gives none). Sets Size to the whole
/// component's voxel count and WholeId to its number (the same on every rank); with `outside`
/// (the background's TouchesBorder), a component reaches the outside where any part of it does,
/// or where the next piece has its voxels as the outside.
void Join(vtkMultiProcessController* controller, const vtkCBC3DPieces::SlabPlan& plan, const int extent[6],
  const cbc3d::LabelImage& image, cbc3d::RunComponents& components, std::vector<char>* outside);
} // namespace vtkCBC3DComponentJoin

#endif
