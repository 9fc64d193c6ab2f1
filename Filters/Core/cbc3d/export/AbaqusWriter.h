#ifndef cbc3d_AbaqusWriter_h
#define cbc3d_AbaqusWriter_h

#include "cbc3d/base/Status.h"
#include "cbc3d/base/TaggedMesh.h"

#include <ostream>

namespace cbc3d
{
/// Writes an Abaqus input file (.inp, also read by CalculiX): *NODE, *ELEMENT TYPE=C3D4 (VTK's
/// node order, positive volumes), an *ELSET tissue_<label> per tissue, and an element-face
/// *SURFACE per boundary and interface (boundary_<label>, interface_<a>_<b>) on the faces of
/// the tets of its first side (the lower label of an interface), through one element set per
/// C3D4 face (<surface>_S1 .. _S4: faces 1-2-3, 1-4-2, 2-4-3, 3-4-1).
Status WriteAbaqus(const TaggedMesh& mesh, std::ostream& out);
} // namespace cbc3d

#endif
