#include "StopSignals.h"

#include "cbc3d/export/PendingFiles.h"

#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>

#include <atomic>
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

const char* const OutOfMemory = "out of memory: try a larger --bcc-size, or a machine with more memory";

// Set when VTK reports an allocation it could not make: Debian builds VTK without NDEBUG, so
// its arrays call abort() right after the report instead of throwing std::bad_alloc.
volatile std::sig_atomic_t VtkAllocationFailed = 0;

// Keeps VTK's messages off the terminal (every error the user needs arrives through an
// ErrorCapture as one line) and notes the one that announces VTK's abort().
class QuietOutputWindow : public vtkOutputWindow
{
public:
  static QuietOutputWindow* New();
  vtkTypeMacro(QuietOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override
  {
    if (text && std::strstr(text, "Unable to allocate"))
    {
      VtkAllocationFailed = 1;
    }
  }
};
vtkStandardNewMacro(QuietOutputWindow);

// Out of memory inside a parallel region can end several threads at once, each in the
// terminate handler: the first one through reports and exits, the others wait for that (two
// interleaved reports were seen under an address-space limit).
std::atomic_flag Ending = ATOMIC_FLAG_INIT;
void WaitIfAnotherThreadIsEnding()
{
  if (Ending.test_and_set())
    for (;;)
      pause();
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
  WaitIfAnotherThreadIsEnding();
  cbc3d::PendingFiles::RemoveAll();
  try
  {
    if (std::current_exception())
      std::rethrow_exception(std::current_exception());
    WriteError("unexpected error");
  }
  catch (const std::bad_alloc&)
  {
    WriteError(OutOfMemory);
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

// An abort() that is not ours: VTK's after a failed allocation (see VtkAllocationFailed), or a
// library's check. One line instead of a core dump, and no file left behind.
void OnAbort(int)
{
  WaitIfAnotherThreadIsEnding();
  cbc3d::PendingFiles::RemoveAll();
  WriteError(VtkAllocationFailed ? OutOfMemory : "aborted by a library (internal error)");
  _exit(1);
}
} // namespace

void SilenceVtkMessages()
{
  vtkNew<QuietOutputWindow> window;
  vtkOutputWindow::SetInstance(window);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

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
  std::signal(SIGABRT, OnAbort);
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
