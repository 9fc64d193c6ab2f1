"""Helpers for the CLI fault tests: run the command under resource limits, check that it failed
with one 'cbc3d: error:' line, and list what a failed run left in a folder."""
import os
import resource
import signal
import subprocess

CLI = os.environ["CBC3D_CLI"]
SOURCE = os.environ["CBC3D_SOURCE_DIR"]


def limits(file_size=None, address_space=None):
    """A preexec_fn setting RLIMIT_FSIZE / RLIMIT_AS in the child; with SIGXFSZ ignored a write
    past the file-size limit fails with EFBIG instead of killing the process."""
    def apply():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        if file_size is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (file_size, file_size))
        if address_space is not None:
            resource.setrlimit(resource.RLIMIT_AS, (address_space, address_space))
    return apply


def run(args, timeout=120, **limit):
    return subprocess.run([CLI] + list(args), capture_output=True, text=True, timeout=timeout,
                          preexec_fn=limits(**limit) if limit else None)


def failure_problems(result, fragment=None):
    """What is wrong with `result` as a failed run: [] when it exited non-zero (not by a signal)
    with exactly one 'cbc3d: error:' line on stderr that mentions `fragment`."""
    problems = []
    lines = [l for l in result.stderr.splitlines() if l.strip()]
    if result.returncode == 0:
        problems.append("exit code 0")
    elif result.returncode < 0:
        problems.append("killed by signal %d" % -result.returncode)
    if len(lines) != 1 or not lines[0].startswith("cbc3d: error: "):
        problems.append("stderr is not one 'cbc3d: error:' line: %r" % result.stderr[-2000:])
    elif fragment and fragment.lower() not in lines[0].lower():
        problems.append("message %r does not mention %r" % (lines[0], fragment))
    return problems


def files_in(folder):
    return sorted(os.listdir(folder))
