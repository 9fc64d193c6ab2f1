/**
 * @file vtkCBC3DSeams.h
 * @brief Where the pieces of MPI ranks meet: who owns which tet, one position per border point,
 *        and the check that the pieces fit (private).
 *
 * Every rank meshes its slab with a halo, so the tets near a slab border exist on both ranks.
 * A tet belongs to the rank whose slab holds its centre, decided on the integer keys of its
 * undeformed corners (vtkCBC3DPieces), so the ranks agree without talking. A point on a border
 * moves where the rank whose slab holds it put it. The ranks then compare the faces on their
 * borders: a face one rank has and its neighbour lacks means the pieces do not fit, and every
 * rank says so rather than leave a crack in the mesh.
 */
#ifndef vtkCBC3DSeams_h
#define vtkCBC3DSeams_h

#include <cstdint>
#include <string>
#include <vector>

class vtkMultiProcessController;
class vtkUnstructuredGrid;

namespace vtkCBC3DSeams
{
/// What the seam step measured, summed over the ranks.
struct SeamReport
{
  long long BorderPoints = 0; // points moved to their owner's position
  long long BorderFaces = 0;  // faces between tets of two ranks
  long long MissingPoints = 0;
  long long UnmatchedFaces = 0;
};

/**
 * Keeps the tets of `mesh` (with GlobalIds) that this rank owns in `owned`, border points at
 * their owners' positions. `cutKeys` holds, for each rank border along `axis`, the key of the
 * plane between the slabs (the ranks' number less one values). A collective call. False, with
 * `error` on every rank, where the pieces do not fit.
 */
bool KeepOwnedTets(vtkMultiProcessController* controller, int axis, const std::vector<std::int64_t>& cutKeys,
  vtkUnstructuredGrid* mesh, vtkUnstructuredGrid* owned, SeamReport& report, std::string& error);
} // namespace vtkCBC3DSeams

#endif
