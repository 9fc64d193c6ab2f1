#ifndef cbc3d_AtomicFile_h
#define cbc3d_AtomicFile_h

#include <functional>
#include <string>

namespace cbc3d
{
/// Runs `write(temporary, error)` on a temporary name beside `path` (same folder, so the rename
/// cannot cross file systems) and renames the file into place when it succeeds, so that `path`
/// appears whole or not at all; on failure the temporary file is removed and `error` says why.
/// The temporary file is in PendingFiles while it exists, so a stop signal removes it too.
bool WriteAtomically(const std::string& path, std::string& error,
  const std::function<bool(const std::string&, std::string&)>& write);

/// The temporary name WriteAtomically uses for `path`: `path.part-PID`.
std::string TemporaryPath(const std::string& path);

/// Renames `temporary` to `path`; entered in PendingFiles first when finished files are held.
bool MoveIntoPlace(const std::string& temporary, const std::string& path, std::string& error);

/// Writes `bytes` to the file `path` with every write and the close checked (a full disk or a
/// file-size limit gives an error here, not a short file); `error` is strerror's text.
bool WriteFileBytes(const std::string& path, const std::string& bytes, std::string& error);
} // namespace cbc3d

#endif
