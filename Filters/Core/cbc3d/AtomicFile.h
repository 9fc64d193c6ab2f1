#ifndef cbc3d_AtomicFile_h
#define cbc3d_AtomicFile_h

#include <functional>
#include <string>

namespace cbc3d
{
/// Runs `write(temporary, error)` on a temporary name beside `path` (same folder, so the rename
/// cannot cross file systems) and renames the file into place when it succeeds, so that `path`
/// appears whole or not at all; on failure the temporary file is removed and `error` says why.
bool WriteAtomically(const std::string& path, std::string& error,
  const std::function<bool(const std::string&, std::string&)>& write);
} // namespace cbc3d

#endif
