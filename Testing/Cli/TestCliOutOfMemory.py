"""Running out of memory anywhere (address-space limits from just above what the command needs
to start up to what a whole run needs, so the allocation that fails falls in reading, the
lattice, refinement's and deformation's parallel loops, quality or writing): every run either
succeeds or ends with one 'cbc3d: error:' line and a non-zero exit, never an abort, and leaves
no file behind. At least one run must run out of memory, or the test proves nothing."""
import os
import sys
import tempfile

from cli_faults import SOURCE, failure_problems, files_in, run

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from cbc3d_testing import Checks  # noqa: E402

PHANTOM = os.path.join(SOURCE, "Data", "nested_shells.vti")
MiB = 1024 * 1024
check = Checks()


def smallest_working_limit():
    """The address space `cbc3d --version` needs (its libraries mapped), to 16 MiB above."""
    low, high = 16 * MiB, 4096 * MiB
    while high - low > 16 * MiB:
        middle = (low + high) // 2
        if run(["--version"], address_space=middle).returncode == 0:
            high = middle
        else:
            low = middle
    return high


with tempfile.TemporaryDirectory() as work:
    base = smallest_working_limit()
    print("cbc3d --version needs about %d MiB of address space" % (base // MiB))
    out_of_memory = 0
    succeeded = 0
    # Every 2 MiB at first: VTK's arrays abort() on a failed allocation (Debian's VTK keeps its
    # debug check), and only a few MiB of limits fail there; the libraries' thread stacks too.
    for extra in list(range(8, 80, 2)) + [96, 128, 160, 256, 448, 1024, 2048]:
        limit = base + extra * MiB
        folder = os.path.join(work, str(extra))
        os.mkdir(folder)
        args = [PHANTOM, "-o", os.path.join(folder, "m.vtu"), "-o", os.path.join(folder, "m.xdmf"),
                "--report", os.path.join(folder, "m.json"), "--bcc-size", "1", "--threads", "2",
                "--quiet"]
        result = run(args, timeout=300, address_space=limit)
        if result.returncode == 0:
            succeeded += 1
            check(files_in(folder) == ["m.h5", "m.json", "m.vtu", "m.xdmf"],
                  "limit +%d MiB: succeeds and writes every file" % extra)
            break  # larger limits succeed too
        problems = failure_problems(result)
        left = files_in(folder)
        if left:
            problems.append("files left behind: %s" % left)
        out_of_memory += "out of memory" in result.stderr
        check(not problems, "limit +%d MiB: %s%s" % (extra, result.stderr.strip()[:150],
                                                     "" if not problems else " PROBLEMS: %s" % problems))
    check(out_of_memory >= 3, "at least three limits ran out of memory (%d did)" % out_of_memory)
    check(succeeded >= 1, "the largest limits let the run finish (%d did)" % succeeded)

check.finish()
