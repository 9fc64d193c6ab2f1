"""The same mesh, byte for byte, for any thread count (1, 2, 4) and from run to run: on the
bundled phantoms, and (1 and 4 threads) on a real image where ../shared/data is present
(skipped otherwise)."""
import filecmp
import os
import sys
import tempfile

from cli_faults import SOURCE, run

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from cbc3d_testing import Checks  # noqa: E402

check = Checks()
FORMATS = [".vtu", ".msh", ".exo"]


def outputs(image, options, threads, folder):
    os.mkdir(folder)
    args = [image, "--quiet", "--threads", str(threads)] + options
    for ext in FORMATS:
        args += ["-o", os.path.join(folder, "m" + ext)]
    result = run(args, timeout=300)
    check(result.returncode == 0, "%s with %d threads runs (%s)" % (os.path.basename(image), threads,
                                                                   result.stderr.strip()))
    return [os.path.join(folder, "m" + ext) for ext in FORMATS]


def same_for_any_threads(image, options, work, counts=(1, 2, 4, 4)):
    name = os.path.basename(image)
    runs = [(threads, outputs(image, options, threads, os.path.join(work, "%s-%d-%d" % (name, threads, n))))
            for n, threads in enumerate(counts)]
    reference = runs[0][1]
    for threads, files in runs[1:]:
        for first, other in zip(reference, files):
            check(os.path.exists(other) and filecmp.cmp(first, other, shallow=False),
                  "%s %s: %s with %d threads is the 1-thread file, byte for byte"
                  % (name, " ".join(options), os.path.basename(other), threads))


with tempfile.TemporaryDirectory() as work:
    for phantom, options in [("nested_shells.vti", ["--bcc-size", "3"]),
                             ("oblique_ball.vti", ["--bcc-size", "3"])]:
        same_for_any_threads(os.path.join(SOURCE, "Data", phantom), options, work)
    shared = os.environ.get("CBC3D_SHARED_DATA", "")
    brain = os.path.join(shared, "cbc3d-brain.nii.gz")
    if os.path.isfile(brain):
        same_for_any_threads(brain, ["--bcc-size", "8"], work, counts=(1, 4))  # (a long run)
    else:
        print("SKIP the real image: no %r (real images live in ../shared/data)" % brain)

check.finish()
