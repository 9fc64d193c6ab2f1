#ifndef cbc3d_BinaryFormats_h
#define cbc3d_BinaryFormats_h

#include "cbc3d/base/Status.h"
#include "cbc3d/base/TaggedMesh.h"

#include <string>
#include <vector>

namespace cbc3d
{
/// The writers that need the netCDF and HDF5 C libraries (Exodus II, and the .h5 of XDMF) live
/// in a shared library of their own, libcbc3dBinaryFormats.so, loaded the first time a mesh is
/// written in one of those formats. netCDF and HDF5 pull in some forty libraries (curl, TLS,
/// Kerberos, LDAP, ICU) that cost every process about 30 ms to load: a twentieth of a small
/// image's whole run, paid by every run that never writes those formats.
struct BinaryFormatWriters
{
  /// ExodusWriter.h's WriteExodus.
  Status (*WriteExodus)(const TaggedMesh& mesh, const std::string& path);
  /// Hdf5HeavyData.h's MakeXdmfHeavyData.
  std::string (*MakeXdmfHeavyData)(const TaggedMesh& mesh, std::string& image);
};

/// The writers, loaded on the first call (once per process, thread-safe); null where the
/// library cannot be loaded, with `error` saying where it was looked for and why it failed.
const BinaryFormatWriters* LoadBinaryFormatWriters(std::string& error);

/// Where the library is looked for, in order, for a program or library at `objectPath` (the
/// file that holds this code): beside it, then in `libraryFolder` beside its folder (bin/cbc3d
/// -> lib/), then by name alone (the caller's run path, LD_LIBRARY_PATH, the system).
std::vector<std::string> BinaryFormatsCandidates(
  const std::string& objectPath, const std::string& libraryFolder);

/// The library's file name.
constexpr const char* BinaryFormatsLibrary = "libcbc3dBinaryFormats.so";
} // namespace cbc3d

/// The library's one entry point, found with dlsym.
extern "C" const cbc3d::BinaryFormatWriters* cbc3dBinaryFormatWriters();

#endif
