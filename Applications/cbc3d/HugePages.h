#ifndef cbc3d_HugePages_h
#define cbc3d_HugePages_h

#include <vector>

/// Replaces this process with `program` (the same arguments), with glibc's malloc asking the
/// kernel for transparent huge pages: the tunable glibc.malloc.hugetlb=1 added to
/// GLIBC_TUNABLES, which glibc reads only when a process starts. Where the user set that
/// tunable (any value, "0" included) it is left as it is. The `held` signals that arrive while
/// `program` starts are blocked (a blocked signal stays pending across the exec) until it calls
/// ReleaseHeldSignals. Returns only when the exec failed, with errno saying why and the
/// environment and signal mask as they were.
void RunWithHugePages(const char* program, char* argv[], const std::vector<int>& held);

/// In the program started by RunWithHugePages, once its own handlers are in place: unblocks the
/// signals RunWithHugePages held (those it blocked itself), so that one sent meanwhile is
/// handled now. Does nothing in a process that was not started that way.
void ReleaseHeldSignals();

#endif
