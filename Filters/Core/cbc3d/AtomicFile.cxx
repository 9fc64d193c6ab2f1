#include "cbc3d/AtomicFile.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <unistd.h>

namespace cbc3d
{
bool WriteAtomically(const std::string& path, std::string& error,
  const std::function<bool(const std::string&, std::string&)>& write)
{
  const std::string temporary = path + ".part-" + std::to_string(getpid());
  if (!write(temporary, error))
  {
    std::remove(temporary.c_str());
    return false;
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    error = "cannot write '" + path + "': " + std::strerror(errno);
    std::remove(temporary.c_str());
    return false;
  }
  return true;
}
} // namespace cbc3d
