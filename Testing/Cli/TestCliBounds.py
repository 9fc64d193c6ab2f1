"""Every option at its extremes: values that cannot work are refused before any work with one
'cbc3d: error:' line naming the reason, a non-zero exit and no output; values that can work
end, within a time limit (a hang fails the test), with a mesh."""
import json
import os
import subprocess
import sys
import tempfile
import time

from cli_faults import SOURCE, failure_problems, files_in, run

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from cbc3d_testing import Checks  # noqa: E402

BALL = os.path.join(SOURCE, "Data", "ball.vti")  # 32 voxels of 1 mm across
check = Checks()

REFUSED = [
    (["--threads", "100000"], "--threads"),
    (["--threads", "1025"], "--threads"),
    (["--threads", "99999999999"], "--threads"),
    (["--bcc-size", "1e308"], "larger than the image"),
    (["--bcc-size", "33"], "larger than the image"),
    (["--bcc-size", "inf"], "--bcc-size"),
    (["--bcc-size", "-inf"], "--bcc-size"),
    (["--bcc-size", "nan"], "--bcc-size"),
    (["--bcc-size", "1e-308"], "memory"),
    (["--iterations", "1001"], "--iterations"),
    (["--iterations", "2147483647"], "--iterations"),
    (["--iterations", "99999999999"], "--iterations"),
    (["--fidelity", "nan"], "--fidelity"),
    (["--fidelity", "inf"], "--fidelity"),
    (["--fidelity", "-1e-300"], "--fidelity"),
    (["--fidelity", "1.0000001"], "--fidelity"),
    (["--boundary-distance", "nan"], "--boundary-distance"),
    (["--boundary-distance", "inf"], "--boundary-distance"),
    (["--boundary-distance", "-inf"], "--boundary-distance"),
]

# (options, seconds allowed): generous for a loaded 2-core machine, far below a hang.
BOUNDED = [
    (["--threads", "1024", "--bcc-size", "4", "--iterations", "1"], 60),
    (["--bcc-size", "32"], 60),
    (["--bcc-size", "12", "--fidelity", "1"], 60),
    (["--fidelity", "1e-300"], 60),
    (["--boundary-distance", "0"], 60),
    (["--boundary-distance", "1e-300"], 120),
    (["--boundary-distance", "1e308"], 60),
    (["--boundary-distance", "-1e308"], 60),
]

with tempfile.TemporaryDirectory() as work:
    for options, fragment in REFUSED:
        out = os.path.join(work, "refused.vtu")
        start = time.monotonic()
        try:
            result = run([BALL, "-o", out] + options, timeout=30)
        except subprocess.TimeoutExpired:
            check(False, "%s: refused within 30 s (it hung)" % " ".join(options))
            continue
        problems = failure_problems(result, fragment)
        if files_in(work):
            problems.append("files left: %s" % files_in(work))
        check(not problems, "%s refused in %.2f s: %s%s" % (" ".join(options), time.monotonic() - start,
              result.stderr.strip(), "" if not problems else " PROBLEMS: %s" % problems))
    for options, seconds in BOUNDED:
        out = os.path.join(work, "bounded.vtu")
        start = time.monotonic()
        try:
            result = run([BALL, "-o", out, "--quiet"] + options, timeout=seconds)
        except subprocess.TimeoutExpired:
            check(False, "%s: ends within %d s (it did not)" % (" ".join(options), seconds))
            continue
        check(result.returncode == 0 and os.path.exists(out),
              "%s: a mesh in %.2f s (limit %d s) %s" % (" ".join(options), time.monotonic() - start,
                                                         seconds, result.stderr.strip()))
        if os.path.exists(out):
            os.remove(out)

    # A huge iteration count: the deformation stops once the surface settles, and says so.
    report = os.path.join(work, "settled.json")
    result = run([BALL, "-o", os.path.join(work, "settled.vtu"), "--quiet", "--iterations", "1000",
                  "--report", report], timeout=60)
    deformation = json.load(open(report))["deformation"] if result.returncode == 0 else {}
    check(0 < deformation.get("iterations", 0) < 100 and "settled" in deformation.get("stop_reason", ""),
          "--iterations 1000 stops once the surface settles: %s" % deformation)

check.finish()
