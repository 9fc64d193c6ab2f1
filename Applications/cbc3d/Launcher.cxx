// The cbc3d command: starts the mesher (libexec/cbc3d/cbc3d beside this program's folder) with
// glibc's malloc asking for huge pages (HugePages.h) and its OpenMP threads waiting briefly
// (ThreadWaits.h). It links neither VTK nor the core, so it starts in about a millisecond where
// the mesher takes 40 ms or more to load its libraries.
#include "HugePages.h"
#include "StopSignals.h"
#include "ThreadWaits.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <unistd.h>

#ifndef CBC3D_MESHER_FROM_BIN
#error "CBC3D_MESHER_FROM_BIN: the mesher's path relative to this program's folder"
#endif

int main(int, char* argv[])
{
  // This program's path: from /proc (links resolved), else as it was started with a folder.
  char self[4096];
  const ssize_t length = readlink("/proc/self/exe", self, sizeof(self) - 1);
  const std::string program = length > 0 ? std::string(self, std::size_t(length))
    : argv[0] && std::strchr(argv[0], '/')  ? std::string(argv[0])
                                            : std::string();
  if (program.empty())
  {
    std::fprintf(stderr, "cbc3d: error: cannot find this program's folder (/proc/self/exe: %s); "
                         "run it with its path\n",
      std::strerror(errno));
    return 1;
  }
  const std::string mesher =
    program.substr(0, program.find_last_of('/') + 1) + CBC3D_MESHER_FROM_BIN;
  ShortenThreadWaits();
  RunWithHugePages(mesher.c_str(), argv, StopSignalNumbers());
  std::fprintf(stderr, "cbc3d: error: cannot run the mesher %s: %s\n", mesher.c_str(),
    std::strerror(errno));
  return 1;
}
