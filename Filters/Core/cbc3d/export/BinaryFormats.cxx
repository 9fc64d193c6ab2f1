#include "cbc3d/export/BinaryFormats.h"

#include <dlfcn.h>
#include <unistd.h>

#include <mutex>

#ifndef CBC3D_INSTALL_LIBDIR
#define CBC3D_INSTALL_LIBDIR "lib"
#endif

namespace cbc3d
{
namespace
{
std::string FolderOf(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

// The file that holds this code: the cbc3d program, libvtkCBC3DFilters.so (ParaView, C++
// users) or a test program. dladdr can name the main program as it was typed (relative to
// where it started), so the program's own path comes too.
std::vector<std::string> ObjectPaths()
{
  std::vector<std::string> paths;
  Dl_info info;
  if (dladdr(reinterpret_cast<void*>(&LoadBinaryFormatWriters), &info) != 0 && info.dli_fname &&
    info.dli_fname[0] != '\0')
    paths.emplace_back(info.dli_fname);
  char program[4096];
  const ssize_t length = readlink("/proc/self/exe", program, sizeof(program) - 1);
  if (length > 0)
    paths.emplace_back(program, std::size_t(length));
  return paths;
}

const BinaryFormatWriters* Load(std::string& error)
{
  std::vector<std::string> candidates;
  for (const std::string& object : ObjectPaths())
  {
    for (const std::string& candidate : BinaryFormatsCandidates(object, CBC3D_INSTALL_LIBDIR))
    {
      bool seen = false;
      for (const std::string& earlier : candidates)
        seen = seen || earlier == candidate;
      if (!seen)
        candidates.push_back(candidate);
    }
  }
  std::string tried, reason;
  bool reasonIsAbsence = true;
  for (const std::string& path : candidates)
  {
    tried += (tried.empty() ? "" : ", ") + path;
    void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library)
    {
      // Say why a library that is there failed (a missing netCDF, say) rather than where
      // there is none.
      const char* said = dlerror();
      const std::string why = said ? said : path + ": cannot be loaded";
      const bool absence = why.rfind(path + ": cannot open shared object file", 0) == 0;
      if (reason.empty() || (reasonIsAbsence && !absence))
      {
        reason = why;
        reasonIsAbsence = absence;
      }
      continue;
    }
    using Entry = const BinaryFormatWriters* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(library, "cbc3dBinaryFormatWriters"));
    if (entry && entry())
      return entry();
    reason = path + " has no writers";
    reasonIsAbsence = false;
    dlclose(library);
  }
  error = std::string("the Exodus II and XDMF writers are in ") + BinaryFormatsLibrary +
    " (with netCDF and HDF5), which could not be loaded: " + reason + " (looked for: " + tried + ")";
  return nullptr;
}
} // namespace

std::vector<std::string> BinaryFormatsCandidates(
  const std::string& objectPath, const std::string& libraryFolder)
{
  const std::string folder = FolderOf(objectPath);
  return { folder + "/" + BinaryFormatsLibrary,
    folder + "/../" + libraryFolder + "/" + BinaryFormatsLibrary, BinaryFormatsLibrary };
}

const BinaryFormatWriters* LoadBinaryFormatWriters(std::string& error)
{
  static std::once_flag once;
  static const BinaryFormatWriters* writers = nullptr;
  static std::string failure;
  std::call_once(once, [] { writers = Load(failure); });
  error = failure;
  return writers;
}
} // namespace cbc3d
