"""SIGINT or SIGTERM while meshing or while writing: the command exits non-zero (128 + the
signal) with one 'cbc3d: error:' line and leaves no file, neither an output nor a temporary
one, even when some outputs of the run had already been written."""
import os
import signal
import subprocess
import sys
import tempfile
import time

from cli_faults import CLI, SOURCE, files_in

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from cbc3d_testing import Checks  # noqa: E402

PHANTOM = os.path.join(SOURCE, "Data", "nested_shells.vti")
MESHES = [".vtu", ".vtk", ".msh", ".inp", ".mesh", ".feb", ".xdmf", ".exo"]
check = Checks()


def command(folder):
    args = [CLI, PHANTOM, "--bcc-size", "1.5", "--report", os.path.join(folder, "m.json"),
            "--surfaces", os.path.join(folder, "s.vtp")]
    for ext in MESHES:
        args += ["-o", os.path.join(folder, "m" + ext)]
    return args


def wait_for(process, folder, moment):
    """Waits until `moment` (seconds after the start, or a test on the folder's names) comes;
    False if the process ended first."""
    start = time.monotonic()
    while process.poll() is None:
        if (time.monotonic() - start >= moment) if isinstance(moment, float) else moment(files_in(folder)):
            return True
        time.sleep(0.0005)
    return False


def stop_at(name, sig, moment, work, tries=4):
    """Sends `sig` at `moment`; a moment in seconds that the run outlives no more (a machine
    less loaded than when the whole run was timed) is tried again at half the time."""
    folder = os.path.join(work, name)
    os.mkdir(folder)
    for attempt in range(tries):
        process = subprocess.Popen(command(folder), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        reached = wait_for(process, folder, moment)
        if reached:
            process.send_signal(sig)
        stdout, stderr = process.communicate(timeout=120)
        if reached or not isinstance(moment, float):
            break
        print("%s: the run ended before %.2f s; again at half that" % (name, moment))
        for leftover in files_in(folder):
            os.remove(os.path.join(folder, leftover))
        moment /= 2
    if not reached:
        check(False, "%s: the run ended (exit %d) before the moment to stop it came" % (name, process.returncode))
        return
    lines = [l for l in stderr.splitlines() if l.strip()]
    left = files_in(folder)
    check(process.returncode == 128 + sig and len(lines) == 1 and lines[0].startswith("cbc3d: error: ")
          and not left, "%s: exit %d, stderr %r, files left %s" % (name, process.returncode, stderr.strip(), left))


with tempfile.TemporaryDirectory() as work:
    started = time.monotonic()
    whole = os.path.join(work, "whole")
    os.mkdir(whole)
    subprocess.run(command(whole), capture_output=True, timeout=300, check=True)
    seconds = time.monotonic() - started
    print("a whole run takes %.2f s and writes %s" % (seconds, files_in(whole)))
    # (Not in the first tenth of a second: before main() installs its handlers, the default
    # action ends the process, with no file made yet.)
    stop_at("sigint_early", signal.SIGINT, 0.2 * seconds, work)
    stop_at("sigterm_meshing", signal.SIGTERM, 0.5 * seconds, work)
    stop_at("sigterm_first_temporary", signal.SIGTERM, lambda names: any(".part-" in n for n in names), work)
    # Outputs already renamed into place: the run's files all go.
    stop_at("sigint_after_first_output", signal.SIGINT, lambda names: any(".part-" not in n for n in names), work)
    stop_at("sigterm_xdmf_written", signal.SIGTERM, lambda names: "m.xdmf" in names, work)

check.finish()
