"""A write that fails (file-size limit, so EFBIG, at several sizes; a folder that cannot be
written) in any output format, the report and the surfaces: one 'cbc3d: error:' line, a
non-zero exit, and no file left, neither an output nor a temporary one."""
import os
import sys
import tempfile

from cli_faults import SOURCE, failure_problems, files_in, run

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from cbc3d_testing import Checks  # noqa: E402

PHANTOM = os.path.join(SOURCE, "Data", "nested_shells.vti")
MESHING = ["--bcc-size", "3", "--iterations", "1"]
MESHES = [".vtu", ".vtk", ".msh", ".inp", ".mesh", ".feb", ".xdmf", ".exo"]
SURFACES = [".vtp", ".vtk", ".stl", ".obj"]
check = Checks()


def sizes_of_every_output(work):
    """One run writing everything: every file's size, to put the limits inside each file."""
    args = [PHANTOM, "--quiet", "--report", os.path.join(work, "m.json")] + MESHING
    for ext in MESHES:
        args += ["-o", os.path.join(work, "m" + ext)]
    result = run(args + ["--surfaces", os.path.join(work, "s.vtp")])
    check(result.returncode == 0, "the run writing every format succeeds (%r)" % result.stderr)
    sizes = {name: os.path.getsize(os.path.join(work, name)) for name in files_in(work)}
    for ext in SURFACES[1:]:
        run([PHANTOM, "--quiet", "-o", os.path.join(work, "m.mesh"), "--surfaces",
             os.path.join(work, "s" + ext)] + MESHING)
        sizes["s" + ext] = os.path.getsize(os.path.join(work, "s" + ext))
    return sizes


def expect_clean_failure(name, args, folder, fragment=None, **limit):
    result = run(args, **limit)
    problems = failure_problems(result, fragment)
    left = files_in(folder)
    if left:
        problems.append("files left behind: %s" % left)
    check(not problems, "%s -> %s%s" % (name, result.stderr.strip()[:140],
                                        "" if not problems else " PROBLEMS: %s" % problems))


with tempfile.TemporaryDirectory() as work:
    full = os.path.join(work, "full")
    os.mkdir(full)
    sizes = sizes_of_every_output(full)
    print("sizes:", sizes)
    out = os.path.join(work, "out")
    os.mkdir(out)
    # Each mesh format alone, its write failing at the first byte, midway and at the last byte
    # (the .xdmf's .h5 is its big file).
    for ext in MESHES:
        size = sizes["m.h5" if ext == ".xdmf" else "m" + ext]
        for limit in sorted({1, size // 2, size - 1}):
            expect_clean_failure("%s, file size limit %d of %d bytes" % (ext, limit, size),
                                 [PHANTOM, "-o", os.path.join(out, "m" + ext)] + MESHING, out,
                                 "cannot write", file_size=limit)
    # The report and the surfaces, beside a small .mesh that fits under the limit: the run's
    # outputs written before the failure go too, so a failed run leaves nothing.
    for name, option in [("m.json", "--report")] + [("s" + e, "--surfaces") for e in SURFACES]:
        size = sizes[name]
        limit = max(sizes["m.mesh"] + 1, size // 2)
        if limit >= size:
            check(False, "%s is larger than m.mesh, so its limit can fall inside it" % name)
            continue
        expect_clean_failure("%s %s, file size limit %d of %d bytes" % (option, name, limit, size),
                             [PHANTOM, "-o", os.path.join(out, "m.mesh"), option,
                              os.path.join(out, name)] + MESHING, out, "cannot write",
                             file_size=limit)
    # Every format in one run, the last ones failing: the ones already written are removed.
    every = [PHANTOM, "--report", os.path.join(out, "m.json"), "--surfaces", os.path.join(out, "s.vtp")]
    for ext in MESHES:
        every += ["-o", os.path.join(out, "m" + ext)]
    expect_clean_failure("every format, limit %d bytes" % (sizes["m.vtu"] + 1), every + MESHING, out,
                         "cannot write", file_size=sizes["m.vtu"] + 1)
    # A folder that cannot be written: a path under a regular file (root ignores permissions).
    blocker = os.path.join(work, "a_file")
    open(blocker, "w").close()
    for ext in MESHES:
        expect_clean_failure("folder under a regular file, %s" % ext,
                             [PHANTOM, "-o", os.path.join(blocker, "m" + ext)] + MESHING, out,
                             "cannot write")
    if os.geteuid() != 0:
        locked = os.path.join(work, "locked")
        os.mkdir(locked, 0o555)
        expect_clean_failure("read-only folder", [PHANTOM, "-o", os.path.join(locked, "m.vtu")] + MESHING,
                             locked, "cannot write")
    else:
        print("SKIP read-only folder: running as root, whom permissions do not stop "
              "(a path under a regular file is checked instead)")

check.finish()
