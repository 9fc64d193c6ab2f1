#ifndef cbc3d_HugePages_h
#define cbc3d_HugePages_h

#include <vector>

/// Runs this program again, once, with glibc's malloc asking the kernel for transparent huge
/// pages (the tunable glibc.malloc.hugetlb=1; glibc reads tunables only when a process starts).
/// Returns only when it did not: the tunable was already set (by the user, or by this call
/// in the process it replaced), or the program could not be run again. Changes no result.
/// The `held` signals that arrive while the program starts again are blocked (a blocked
/// signal stays pending across the exec) until the new process calls ReleaseHeldSignals.
void RunAgainWithHugePages(char* argv[], const std::vector<int>& held);

/// In the process run again, once its own handlers are in place: unblocks the signals
/// RunAgainWithHugePages held (those it blocked itself), so that one sent meanwhile is handled
/// now. Does nothing in a process that was not run again.
void ReleaseHeldSignals();

#endif
