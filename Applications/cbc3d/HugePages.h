#ifndef cbc3d_HugePages_h
#define cbc3d_HugePages_h

/// Runs this program again, once, with glibc's malloc asking the kernel for transparent huge
/// pages (the tunable glibc.malloc.hugetlb=1; glibc reads tunables only when a process starts).
/// Returns only when it did not: the tunable was already set (by the user, or by this call
/// in the process it replaced), or the program could not be run again. Changes no result.
void RunAgainWithHugePages(char* argv[]);

#endif
