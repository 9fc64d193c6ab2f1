#ifndef cbc3d_PendingFiles_h
#define cbc3d_PendingFiles_h

#include <string>

namespace cbc3d
{
/// Files that must vanish if the process is stopped before it finishes: the temporary files
/// being written and, while a run holds them (HoldFinishedFiles), the outputs it has already
/// renamed into place. A fixed table, so that a signal handler can remove them: a handler may
/// not allocate or lock, but may walk static memory and call unlink().
namespace PendingFiles
{
/// Enters `path`; returns its slot, or -1 when the table is full or the path too long (the
/// file is then still removed on the ordinary error paths, only not from a signal handler).
int Add(const std::string& path);

/// Forgets the file in `slot` (nothing for -1); the file itself is left alone.
void Forget(int slot);

/// Removes every file in the table and forgets them. Async-signal-safe.
void RemoveAll() noexcept;

/// Forgets every file in the table, leaving the files: the run has finished.
void ForgetAll() noexcept;

/// Whether outputs renamed into place stay in the table (until RemoveAll or ForgetAll), so that
/// a run writing several files leaves all of them or none. Off by default (one file per call,
/// as in ParaView's Save Data).
void HoldFinishedFiles(bool hold);
bool HoldingFinishedFiles();
} // namespace PendingFiles
} // namespace cbc3d

#endif
