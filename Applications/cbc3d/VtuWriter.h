#ifndef cbc3d_VtuWriter_h
#define cbc3d_VtuWriter_h

#include <string>

class vtkUnstructuredGrid;

/// Makes in memory the .vtu file that vtkXMLUnstructuredGridWriter makes with inline binary
/// data, zlib and UInt32 headers (VTK/ParaView 5.11), byte for byte, but compresses and
/// base64-encodes the 32 KiB blocks on `threads` OpenMP threads (0: all). Returns false, with
/// `bytes` untouched, for what it does not reproduce (arrays other than plain numeric ones,
/// polyhedra, 32-bit cell arrays, a grid without points or cell types, information keys other
/// than non-empty double vectors, a time step): the caller then uses VTK's writer. Computes the arrays' ranges with VTK's GetRange as VTK's writer does, which caches
/// them in the arrays, but for big one-component integer arrays, whose min and max it finds on
/// the threads.
bool MakeVtuBytes(vtkUnstructuredGrid* mesh, int threads, std::string& bytes);

#endif
