#include "cbc3d/export/AtomicFile.h"

#include "cbc3d/export/PendingFiles.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace cbc3d
{
std::string TemporaryPath(const std::string& path)
{
  return path + ".part-" + std::to_string(getpid());
}

bool MoveIntoPlace(const std::string& temporary, const std::string& path, std::string& error)
{
  if (PendingFiles::HoldingFinishedFiles())
  {
    PendingFiles::Add(path); // before the rename, so that no moment leaves it unlisted
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    error = "cannot write '" + path + "': " + std::strerror(errno);
    return false;
  }
  return true;
}

bool WriteAtomically(const std::string& path, std::string& error,
  const std::function<bool(const std::string&, std::string&)>& write)
{
  const std::string temporary = TemporaryPath(path);
  const int slot = PendingFiles::Add(temporary);
  const bool written = write(temporary, error) && MoveIntoPlace(temporary, path, error);
  if (!written)
  {
    std::remove(temporary.c_str());
  }
  PendingFiles::Forget(slot);
  return written;
}

bool WriteFileBytes(const std::string& path, const std::string& bytes, std::string& error)
{
  const int file = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (file < 0)
  {
    error = std::strerror(errno);
    return false;
  }
  std::size_t done = 0;
  while (done < bytes.size())
  {
    const ssize_t n = ::write(file, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      error = std::strerror(n < 0 ? errno : ENOSPC);
      close(file);
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  if (close(file) != 0)
  {
    error = std::strerror(errno);
    return false;
  }
  return true;
}
} // namespace cbc3d
