#ifndef cbc3d_Hdf5HeavyData_h
#define cbc3d_Hdf5HeavyData_h

#include "cbc3d/base/TaggedMesh.h"

#include <string>

namespace cbc3d
{
/// The datasets of the .h5, as dolfinx's XDMFFile names them.
constexpr const char* MeshTopology = "/Mesh/mesh/topology";
constexpr const char* MeshGeometry = "/Mesh/mesh/geometry";
constexpr const char* TissueValues = "/MeshTags/tissues/Values";
constexpr const char* SurfaceTopology = "/MeshTags/surfaces/topology";
constexpr const char* SurfaceValues = "/MeshTags/surfaces/Values";

/// The bytes of the HDF5 file beside an .xdmf (XdmfWriter.h says what it holds), made in
/// memory; "" when made, else what failed. In libcbc3dBinaryFormats.so (BinaryFormats.h).
std::string MakeXdmfHeavyData(const TaggedMesh& mesh, std::string& image);
} // namespace cbc3d

#endif
