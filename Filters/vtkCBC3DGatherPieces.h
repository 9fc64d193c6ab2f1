/**
 * @file vtkCBC3DGatherPieces.h
 * @brief One mesh on rank 0 from the pieces of every MPI rank (private).
 *
 * vtkCBC3DMeshWriter writes one whole file from a parallel run. The mesher's pieces carry
 * compact GlobalIds (0 to the points less one over the whole mesh), so a point on a rank border
 * that two pieces hold becomes one point again. A single piece with data (a serial result that
 * ParaView keeps on rank 0) is taken as it is.
 */
#ifndef vtkCBC3DGatherPieces_h
#define vtkCBC3DGatherPieces_h

#include <vtkSmartPointer.h>

#include <string>

class vtkMultiProcessController;
class vtkUnstructuredGrid;

namespace vtkCBC3DGatherPieces
{
/// A collective call. On rank 0, `whole` is the merged mesh, or `error` says why there is none;
/// the other ranks get nothing.
void Gather(vtkMultiProcessController* controller, vtkUnstructuredGrid* piece,
  vtkSmartPointer<vtkUnstructuredGrid>& whole, std::string& error);
} // namespace vtkCBC3DGatherPieces

#endif
