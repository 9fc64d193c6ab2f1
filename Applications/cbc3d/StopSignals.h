#ifndef cbc3d_StopSignals_h
#define cbc3d_StopSignals_h

#include <csignal>
#include <vector>

/// Makes the command end cleanly however it is stopped: SIGINT, SIGTERM and SIGHUP remove every
/// file of the run (cbc3d::PendingFiles: the temporary files and the outputs already renamed)
/// and exit with 128 + the signal's number after one line on stderr; SIGXFSZ is ignored, so a
/// file-size limit fails the write (EFBIG) instead of killing the process; and an exception
/// that reaches std::terminate (one escaping an OpenMP region, where it cannot be caught
/// outside) gives one line and exit code 1 instead of an abort, the files removed too; so does
/// an abort() in a library (VTK's arrays abort when an allocation fails).
void InstallStopHandlers();

/// Keeps VTK's own messages off the terminal: errors reach the user through ErrorCapture, as
/// one line. Also lets the abort handler tell VTK's out-of-memory abort from others.
void SilenceVtkMessages();

/// The signals InstallStopHandlers makes end a run cleanly: SIGINT, SIGTERM and SIGHUP (inline:
/// the launcher holds them without linking the handlers).
inline std::vector<int> StopSignalNumbers()
{
  return { SIGINT, SIGTERM, SIGHUP };
}

/// Removes the run's files (the error path) or forgets them (the run finished).
void RemoveRunFiles();
void KeepRunFiles();

#endif
