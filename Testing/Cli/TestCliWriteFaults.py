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
# The lattice alone: quick, with three tissues, so boundaries and interfaces are written.
LATTICE = ["--fidelity", "0", "--iterations", "0", "--bcc-size", "2"]
# A coarse lattice whose mesh file is smaller than the report and the surfaces files.
COARSE = ["--fidelity", "0", "--iterations", "0", "--bcc-size", "16"]
MESHES = [".vtu", ".vtk", ".msh", ".inp", ".mesh", ".feb", ".xdmf", ".exo"]
SURFACES = [".vtp", ".vtk", ".stl", ".obj"]
check = Checks()


def size_alone(work, options, *outputs):
    """The sizes of the files of a run writing `outputs` (option, name) pairs alone (a file's
    bytes can depend on what was written before it: VTK caches array ranges it then writes)."""
    folder = tempfile.mkdtemp(dir=work)
    args = [PHANTOM, "--quiet"] + options
    for option, name in outputs:
        args += [option, os.path.join(folder, name)]
    result = run(args)
    check(result.returncode == 0, "writing %s succeeds (%r)" % (outputs, result.stderr))
    return {name: os.path.getsize(os.path.join(folder, name)) for name in files_in(folder)}


def expect_clean_failure(name, args, folder, fragment=None, **limit):
    result = run(args, **limit)
    problems = failure_problems(result, fragment)
    left = files_in(folder)
    if left:
        problems.append("files left behind: %s" % left)
    check(not problems, "%s -> %s%s" % (name, result.stderr.strip()[:140],
                                        "" if not problems else " PROBLEMS: %s" % problems))


with tempfile.TemporaryDirectory() as work:
    out = os.path.join(work, "out")
    os.mkdir(out)
    # Each mesh format alone, its write failing at the first byte, midway and at the last byte
    # (the .xdmf's .h5 is its big file).
    for ext in MESHES:
        sizes = size_alone(work, LATTICE, ("-o", "m" + ext))
        size = sizes["m.h5" if ext == ".xdmf" else "m" + ext]
        for limit in sorted({1, size // 2, size - 1}):
            expect_clean_failure("%s, file size limit %d of %d bytes" % (ext, limit, size),
                                 [PHANTOM, "-o", os.path.join(out, "m" + ext)] + LATTICE, out,
                                 "File too large", file_size=limit)
    # The report and the surfaces, beside a mesh file that fits under the limit: the mesh,
    # written before the failure, goes too, so a failed run leaves nothing.
    # (.obj text is smaller than any mesh file, but is written out by the same checked code as
    # .stl, .vtp and .vtk; its failure is checked below with a name that cannot be taken.)
    for option, name in [("--report", "m.json")] + [("--surfaces", "s" + e) for e in SURFACES[:-1]]:
        sizes = size_alone(work, COARSE, ("-o", "m.mesh"), (option, name))
        size, mesh = sizes[name], sizes["m.mesh"]
        if not check(mesh + 1 < size, "%s (%d bytes) is larger than the coarse m.mesh (%d)" % (name, size, mesh)):
            continue
        # The report's timings change its length by a few bytes from run to run.
        last = size - (100 if name == "m.json" else 1)
        for limit in sorted({mesh + 1, max(mesh + 1, size // 2), max(mesh + 1, last)}):
            expect_clean_failure("%s %s, file size limit %d of %d bytes" % (option, name, limit, size),
                                 [PHANTOM, "-o", os.path.join(out, "m.mesh"), option,
                                  os.path.join(out, name)] + COARSE, out, "File too large",
                                 file_size=limit)
    # Every format in one run, the larger ones failing: the ones already written go too.
    every = [PHANTOM, "--report", os.path.join(out, "m.json"), "--surfaces", os.path.join(out, "s.vtp")]
    for ext in MESHES:
        every += ["-o", os.path.join(out, "m" + ext)]
    limit = size_alone(work, LATTICE, ("-o", "m.vtu"))["m.vtu"] + 1
    expect_clean_failure("every format, limit %d bytes" % limit, every + LATTICE, out,
                         "File too large", file_size=limit)
    # An output name taken by a folder: the rename fails at the end; the files before it go.
    for option, name in [("-o", "m.vtu"), ("--surfaces", "s.obj"), ("--report", "m.json")]:
        taken = os.path.join(out, name)
        os.makedirs(os.path.join(taken, "inside"))
        result = run([PHANTOM, "-o", os.path.join(out, "m.mesh"), "-o", os.path.join(out, "m.xdmf"),
                      option, taken] + COARSE)
        problems = failure_problems(result, "cannot write")
        if files_in(out) != [name] or files_in(taken) != ["inside"]:
            problems.append("files left: %s" % files_in(out))
        check(not problems, "%s %s taken by a folder -> %s %s" % (option, name, result.stderr.strip(), problems))
        os.rmdir(os.path.join(taken, "inside"))
        os.rmdir(taken)
    # Every geometry-only surfaces file reads back (the .stl and .obj are written here, not by VTK).
    import meshio
    folder = tempfile.mkdtemp(dir=work)
    run([PHANTOM, "-o", os.path.join(folder, "m.mesh"), "--surfaces", os.path.join(folder, "s.vtk")] + COARSE)
    reference = meshio.read(os.path.join(folder, "s.vtk"))
    for ext in (".stl", ".obj"):
        path = os.path.join(folder, "s" + ext)
        run([PHANTOM, "-o", os.path.join(folder, "m" + ext + ".mesh"), "--surfaces", path] + COARSE)
        surfaces = meshio.read(path)
        check(len(surfaces.cells_dict["triangle"]) == len(reference.cells_dict["triangle"])
              and abs(surfaces.points[surfaces.cells_dict["triangle"]] -
                      reference.points[reference.cells_dict["triangle"]]).max() < 1e-4,
              "meshio reads s%s: the triangles of s.vtk" % ext)
    # A folder that cannot be written: a path under a regular file (root ignores permissions).
    blocker = os.path.join(work, "a_file")
    open(blocker, "w").close()
    for ext in MESHES:
        expect_clean_failure("folder under a regular file, %s" % ext,
                             [PHANTOM, "-o", os.path.join(blocker, "m" + ext)] + LATTICE, out,
                             "cannot write")
    if os.geteuid() != 0:
        locked = os.path.join(work, "locked")
        os.mkdir(locked, 0o555)
        expect_clean_failure("read-only folder", [PHANTOM, "-o", os.path.join(locked, "m.vtu")] + LATTICE,
                             locked, "cannot write")
    else:
        print("SKIP read-only folder: running as root, whom permissions do not stop "
              "(a path under a regular file is checked instead)")

check.finish()
