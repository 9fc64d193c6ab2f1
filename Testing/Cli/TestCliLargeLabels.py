"""Labels of any integer type keep their values in every output (issue 16).

Tiny two-tissue phantoms (12 x 10 x 10 voxels, written here as .vti and as NIfTI-1 .nii) with
labels beyond 32 bits (uint32 4,000,000,000; int64 5,000,000,000 and -5,000,000,000) and small
ones (uint8, int16) go through the whole cbc3d pipeline to every format. Each file is read back
with its client (VTK, meshio, gmsh, netCDF4, XML, JSON) and must hold the exact label values.
A large-label image must give the same mesh as one with small labels in the same order (the core
meshes order-preserving codes). Formats whose label fields are 32-bit (Gmsh, Medit, XDMF) refuse
a large label with one line and no file; a uint64 above the largest int64 is refused likewise.

Environment: CBC3D_CLI (the cbc3d executable), CBC3D_TEST_OUTPUT (a folder for the files).
Python: /usr/bin/python3 with numpy, the vtkmodules of python3-paraview, meshio, gmsh, netCDF4.
"""
import json
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from cbc3d_testing import Checks, write_nifti  # noqa: E402

try:
    import meshio
    import netCDF4
    from vtkmodules.util import numpy_support
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOLegacy import vtkUnstructuredGridReader
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter, vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader
except ImportError as error:
    print("SKIP: %s (run with /usr/bin/python3: numpy, python3-paraview, meshio, netCDF4)" % error)
    sys.exit(77)
try:
    import gmsh
except ImportError:
    gmsh = None

CLI = os.environ["CBC3D_CLI"]
OUT = tempfile.mkdtemp(prefix="large-labels-", dir=os.environ.get("CBC3D_TEST_OUTPUT"))
DIMS = (12, 10, 10)
check = Checks()


def phantom(dtype, low, high, background=0):
    """Two boxes side by side (`low` at small x, `high` beside it) in a background, x fastest."""
    labels = np.full(DIMS[::-1], background, dtype=dtype)
    labels[2:8, 2:8, 2:6] = low
    labels[2:8, 2:8, 6:10] = high
    return labels.ravel()


def write_vti(path, labels):
    image = vtkImageData()
    image.SetDimensions(*DIMS)
    array = numpy_support.numpy_to_vtk(labels, deep=1)
    array.SetName("labels")
    image.GetPointData().SetScalars(array)
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


def write_input(name, kind, labels):
    path = os.path.join(OUT, name + kind)
    if kind == ".vti":
        write_vti(path, labels)
    else:
        write_nifti(path, DIMS, [int(v) for v in labels], str(labels.dtype), pixdim=(1.0, 1.0, 1.0, 1.0))
    return path


# For runs that check only how a file tags the tissues: the lattice alone, fast.
LATTICE_ONLY = ("--fidelity", "0", "--iterations", "0")


def run(image, outputs, *options):
    args = [CLI, image, "--bcc-size", "2.5", "--quiet"]
    for output in outputs:
        args += ["-o", output]
    return subprocess.run(args + list(options), capture_output=True, text=True)


def read_grid(path):
    reader = vtkXMLUnstructuredGridReader() if path.endswith(".vtu") else vtkUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    labels = grid.GetCellData().GetArray("Label")
    points = numpy_support.vtk_to_numpy(grid.GetPoints().GetData())
    cells = numpy_support.vtk_to_numpy(grid.GetCells().GetConnectivityArray())
    return 8 * labels.GetDataTypeSize(), numpy_support.vtk_to_numpy(labels).astype(np.int64), points, cells


def check_vtk_files(name, paths, tissues, large):
    kind, labels, points, cells = read_grid(paths[".vtu"])
    want_bits = 64 if large else 32
    check(kind == want_bits, "%s .vtu: Label is a %d-bit array (%d)" % (name, want_bits, kind))
    check(set(labels.tolist()) == set(tissues), "%s .vtu: labels %s" % (name, sorted(set(labels.tolist()))))
    legacy = read_grid(paths[".vtk"])
    check(np.array_equal(legacy[1], labels), "%s .vtk: the same labels per tet" % name)
    for extension in (".vtu", ".vtk"):
        read = np.concatenate(meshio.read(paths[extension]).cell_data["Label"]).ravel()
        check(np.array_equal(read, labels), "%s %s: meshio reads the same labels" % (name, extension))
    return labels, points, cells


def check_named_formats(name, paths, tissues, labels):
    """.inp and .feb name each tissue tissue_<label>; .exo names its blocks so."""
    names = ["tissue_%d" % t for t in sorted(tissues)]
    inp = meshio.read(paths[".inp"], file_format="abaqus")
    sets = {k: len(np.concatenate(v)) for k, v in inp.cell_sets.items() if k.startswith("tissue_")}
    check(sorted(sets) == sorted(names), "%s .inp: element sets %s" % (name, sorted(sets)))
    check(all(sets["tissue_%d" % t] == int((labels == t).sum()) for t in tissues),
          "%s .inp: every tet in its tissue's set" % name)
    feb = ElementTree.parse(paths[".feb"]).getroot()
    check([e.get("name") for e in feb.iter("Elements")] == names, "%s .feb: Elements named %s" % (name, names))
    with netCDF4.Dataset(paths[".exo"]) as exo:
        blocks = [b"".join(row.compressed()).decode() for row in exo.variables["eb_names"][:]]
        ids = exo.variables["eb_prop1"][:].tolist()
    check(blocks == names, "%s .exo: blocks %s" % (name, blocks))
    fit = all(0 < t < 2**31 for t in tissues)
    want_ids = sorted(tissues) if fit else list(range(1, len(tissues) + 1))
    check(ids == want_ids, "%s .exo: block ids %s" % (name, ids))


def check_report_and_surfaces(name, paths, tissues, outside):
    with open(paths[".json"]) as f:
        report = json.load(f)
    check(sorted(report["tissues"]) == sorted(str(t) for t in tissues),
          "%s report: tissues %s" % (name, sorted(report["tissues"])))
    sides = {tuple(s["labels"]) for s in report["surfaces"].values()}
    low, high = sorted(tissues)
    check(sides == {(low, outside), (high, outside), (low, high)}, "%s report: surfaces %s" % (name, sorted(sides)))
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(paths[".vtp"])
    reader.Update()
    boundary = numpy_support.vtk_to_numpy(reader.GetOutput().GetCellData().GetArray("BoundaryLabels"))
    check({tuple(row) for row in boundary.astype(np.int64).tolist()} == sides,
          "%s surfaces: BoundaryLabels hold %s" % (name, sorted(sides)))


def check_int32_formats(name, paths, image, tissues, labels, msh_options):
    """Small labels: Medit refs, and Gmsh tags in both versions (with `msh_options` given: the
    run's options; None skips Gmsh); a label of 0 or less is refused by Gmsh as before."""
    medit = meshio.read(paths[".mesh"])
    refs = np.concatenate([r for c, r in zip(medit.cells, medit.cell_data["medit:ref"]) if c.type == "tetra"])
    check(sorted(refs.tolist()) == sorted(labels.tolist()), "%s .mesh: tet refs are the labels" % name)
    for version in ("4.1", "2.2") if msh_options is not None else ():
        msh = os.path.join(OUT, "%s-%s.msh" % (name, version))
        result = run(image, [msh], "--msh-version", version, *msh_options, *LATTICE_ONLY)
        if min(tissues) <= 0:
            check(result.returncode != 0 and "positive physical tags" in result.stderr,
                  "%s .msh %s: refused for a label of 0 or less, as before" % (name, version))
            continue
        if gmsh is None:
            continue
        gmsh.initialize()
        gmsh.option.setNumber("General.Verbosity", 0)
        gmsh.open(msh)
        groups = {tag: gmsh.model.getPhysicalName(3, tag) for _, tag in gmsh.model.getPhysicalGroups(3)}
        gmsh.finalize()
        check(groups == {t: "tissue_%d" % t for t in tissues}, "%s .msh %s: physical volumes %s" % (name, version, groups))


def check_refusals(name, image):
    """Large labels: the 32-bit formats refuse with one line and leave no file."""
    for extension, options in ((".msh", []), (".msh", ["--msh-version", "2.2"]), (".mesh", []), (".xdmf", [])):
        path = os.path.join(OUT, name + "-refused" + extension)
        result = run(image, [path], *options, *LATTICE_ONLY)
        lines = result.stderr.strip().splitlines()
        # A negative label is refused by Gmsh for its sign first, as a small one always was.
        reason = "cannot hold tissue label" in result.stderr or "positive physical tags" in result.stderr
        check(result.returncode != 0 and len(lines) == 1 and reason,
              "%s %s %s: refused in one line: %s" % (name, extension, " ".join(options), lines))
        left = [f for f in os.listdir(OUT) if f.startswith(name + "-refused")]
        check(not left, "%s %s: no file left (%s)" % (name, extension, left))


def mesh_case(name, image, tissues, large, outside=0, options=(), refusals=True):
    """Meshes `image` to every format that holds its labels and checks them (and, with
    `refusals`, that the others refuse large labels or hold small ones); returns the .vtu's
    labels, points and cells."""
    extensions = [".vtu", ".vtk", ".inp", ".feb", ".exo"] + ([] if large else [".mesh"])
    paths = {e: os.path.join(OUT, name + e) for e in extensions + [".json", ".vtp"]}
    outputs = [paths[e] for e in extensions]
    result = run(image, outputs, "--report", paths[".json"], "--surfaces", paths[".vtp"], *options)
    if not check(result.returncode == 0, "%s: meshed to %s (%s)" % (name, " ".join(extensions), result.stderr.strip())):
        return None
    labels, points, cells = check_vtk_files(name, paths, tissues, large)
    check_named_formats(name, paths, tissues, labels)
    check_report_and_surfaces(name, paths, tissues, outside)
    if large and refusals:
        check_refusals(name, image)
    elif not large:
        check_int32_formats(name, paths, image, tissues, labels, options if refusals else None)
    return labels, points, cells


def same_mesh(name, mesh, twin, mapping):
    """The large-label mesh is the small-label twin's, label for label."""
    if mesh is None or twin is None:
        return
    labels, points, cells = mesh
    check(np.array_equal(points, twin[1]) and np.array_equal(cells, twin[2]),
          "%s: the same points and tets as with small labels in the same order" % name)
    check(np.array_equal(labels, np.vectorize(mapping.get)(twin[0])), "%s: the same tissue per tet" % name)


def main():
    # (name, type, low label, high label, the small-label twin's labels in the same order)
    cases = [("uint32", "uint32", 7, 4000000000, (7, 200)),
             ("int64", "int64", -5000000000, 5000000000, (-3, 1000))]
    for kind in (".vti", ".nii"):
        twins = {}
        for small_type, low, high in (("uint8", 7, 200), ("int16", -3, 1000)):
            name = "%s-%s" % (small_type, kind[1:])
            image = write_input(name, kind, phantom(small_type, low, high))
            twins[(low, high)] = mesh_case(name, image, (low, high), False, refusals=kind == ".vti")
        for name, dtype, low, high, twin in cases:
            name = "%s-%s" % (name, kind[1:])
            image = write_input(name, kind, phantom(dtype, low, high))
            mesh = mesh_case(name, image, (low, high), True, refusals=kind == ".vti")
            same_mesh(name, mesh, twins[twin], {twin[0]: low, twin[1]: high})

    # A large outside label (the first --background) with small tissues: Gmsh still writes them.
    image = write_input("outside", ".vti", phantom("int64", 1, 2, background=5000000000))
    mesh_case("outside-int64", image, (1, 2), False, outside=5000000000, options=("--background", "5000000000"))

    # A uint64 label above the largest int64: one line, no file.
    image = write_input("uint64", ".vti", phantom("uint64", 1, 2**63 + 5))
    output = os.path.join(OUT, "uint64.vtu")
    result = run(image, [output])
    lines = result.stderr.strip().splitlines()
    check(result.returncode != 0 and len(lines) == 1 and str(2**63 + 5) in lines[0],
          "uint64 above int64: refused in one line: %s" % lines)
    check(not os.path.exists(output), "uint64 above int64: no file")
    check.finish()


main()
