#include "StopSignals.h"

#include "cbc3d/PendingFiles.h"

#include <csignal>
#include <cstring>
#include <exception>
#include <new>
#include <unistd.h>

namespace
{
// Only async-signal-safe calls here: unlink (in RemoveAll), write and _exit.
void OnStopSignal(int signal)
{
  cbc3d::PendingFiles::RemoveAll();
  const char* text = signal == SIGINT ? "cbc3d: error: interrupted (SIGINT); no file written\n"
    : signal == SIGTERM              ? "cbc3d: error: terminated (SIGTERM); no file written\n"
                                     : "cbc3d: error: hung up (SIGHUP); no file written\n";
  const ssize_t ignored = write(STDERR_FILENO, text, std::strlen(text));
  static_cast<void>(ignored);
  _exit(128 + signal);
}

void WriteError(const char* message, const char* detail = "")
{
  for (const char* text : { "cbc3d: error: ", message, detail, "\n" })
  {
    const ssize_t ignored = write(STDERR_FILENO, text, std::strlen(text));
    static_cast<void>(ignored);
  }
}

// Called instead of abort() when an exception cannot be caught: out of memory inside a
// parallel region is the one to expect. Writes without allocating: memory may have run out.
void OnTerminate()
{
  cbc3d::PendingFiles::RemoveAll();
  try
  {
    if (std::current_exception())
      std::rethrow_exception(std::current_exception());
    WriteError("unexpected error");
  }
  catch (const std::bad_alloc&)
  {
    WriteError("out of memory: try a larger --bcc-size, or a machine with more memory");
  }
  catch (const std::exception& e)
  {
    WriteError("unexpected error: ", e.what());
  }
  catch (...)
  {
    WriteError("unexpected error");
  }
  _exit(1);
}
} // namespace

void InstallStopHandlers()
{
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = OnStopSignal;
  sigemptyset(&action.sa_mask);
  for (const int signal : StopSignalNumbers())
  {
    sigaddset(&action.sa_mask, signal); // one handler at a time
  }
  for (const int signal : StopSignalNumbers())
  {
    sigaction(signal, &action, nullptr);
  }
  std::signal(SIGXFSZ, SIG_IGN);
  std::set_terminate(OnTerminate);
  cbc3d::PendingFiles::HoldFinishedFiles(true);
}

void RemoveRunFiles()
{
  cbc3d::PendingFiles::RemoveAll();
}

void KeepRunFiles()
{
  cbc3d::PendingFiles::ForgetAll();
}
