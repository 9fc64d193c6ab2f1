# pvpython: the example Documentation/Examples/mesh_nifti.py, run as a user runs it
# (`xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython mesh_nifti.py PLUGIN IMAGE OUT.vtu
# SHOT.png --edge-length 4 --name 1=...`) on Data/shells.nii.gz (1 mm voxels). Checks:
# - exit 0, and the example gives the whole method's mesh, not the lattice's staircase: the
#   figures it prints are those of the cbc3d command at its defaults on the same image and
#   lattice size (tets, points, angles, Hausdorff distance, every tissue's tets); its angles lie
#   within [20, 160] degrees and are not the lattice's 60 and 90; its Hausdorff distance is under
#   1.5 voxels and under half the lattice's alone (the command with --fidelity 0 --iterations 0);
# - the .vtu reads back with those tets, points and labels, refined (RefinementLevel above 0)
#   and deformed (Displacement not zero);
# - the PNG is a real picture (several colours, not one flat tone) whose tissues have a
#   categorical map: the legend's swatch of each tissue, in the example's colour for it.
# Skips (77) without xvfb-run or when Xvfb cannot start.
import json
import os
import shutil
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks  # noqa: E402

source = os.environ["CBC3D_SOURCE_DIR"]
plugin = os.environ["CBC3D_PLUGIN"]
cli = os.environ["CBC3D_CLI"]
work = os.path.join(os.environ["CBC3D_TEST_OUTPUT"], "TestExampleScript")
example = os.path.join(source, "Documentation", "Examples", "mesh_nifti.py")
image = os.path.join(source, "Data", "shells.nii.gz")
LATTICE = "4"     # mm: 4 voxels
VOXEL = 1.0       # mm
# The example's first three colours (its PALETTE), one per tissue in ascending label order.
COLOURS = [(0.90, 0.62, 0.00), (0.34, 0.71, 0.91), (0.00, 0.62, 0.45)]

xvfb_run = shutil.which("xvfb-run")
if xvfb_run is None:
    print("SKIP: xvfb-run is not installed (apt-get install xvfb xauth); the example renders a picture")
    sys.exit(77)
# sys.executable is the Python library's idea of the interpreter, not necessarily pvpython.
pvpython = shutil.which("pvpython") or os.path.join(os.path.dirname(sys.executable), "pvpython")
if not os.path.isfile(pvpython):
    print("SKIP: pvpython not found on PATH")
    sys.exit(77)

shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
mesh_path = os.path.join(work, "shells.vtu")
picture_path = os.path.join(work, "shells.png")
check = Checks()

# -noreset: Xvfb otherwise resets when its first client (ParaView probing the display) leaves, and
# the render window, connecting during the reset, fails ("bad X server connection", SIGABRT);
# seen in about one run in four when two such runs overlap.
command = [xvfb_run, "-a", "-s", "-screen 0 1280x1024x24 -noreset", pvpython, example, plugin, image, mesh_path,
           picture_path, "--edge-length", LATTICE, "--name", "1=outer shell", "--name", "2=middle shell",
           "--name", "3=core"]
print(" ".join(command))
try:
    run = subprocess.run(command, capture_output=True, text=True, timeout=180)
except subprocess.TimeoutExpired:
    check(False, "the example finished within 180 s")
    check.finish()
print(run.stdout)
print(run.stderr, file=sys.stderr)
if run.returncode != 0 and "Xvfb failed to start" in run.stderr:
    print("SKIP: the X server (Xvfb) could not start")
    sys.exit(77)
check(run.returncode == 0, "the example exits 0 (got %d)" % run.returncode)


def cli_report(name, *options):
    path = os.path.join(work, name + ".json")
    subprocess.run([cli, image, "-o", os.path.join(work, name + ".vtu"), "--bcc-size", LATTICE, "--quiet",
                    "--report", path] + list(options), check=True)
    return json.load(open(path))


# The whole method at the command line's defaults on the same image and lattice size: the
# example must print the same mesh's figures.
report = cli_report("cli")
staircase = cli_report("lattice", "--fidelity", "0", "--iterations", "0")
print("command line: %d tets, angles %.2f to %.2f, Hausdorff %.3f mm; the lattice alone %.3f mm"
      % (report["tetrahedra"], report["min_dihedral_deg"], report["max_dihedral_deg"], report["hausdorff_mm"],
         staircase["hausdorff_mm"]))

check("tetrahedra %d, points %d" % (report["tetrahedra"], report["points"]) in run.stdout,
      "the example prints %d tetrahedra and %d points" % (report["tetrahedra"], report["points"]))
angles = "dihedral angles %.2f to %.2f degrees" % (report["min_dihedral_deg"], report["max_dihedral_deg"])
check(angles in run.stdout, "the example prints '%s'" % angles)
check(20.0 - 1e-9 <= report["min_dihedral_deg"] and report["max_dihedral_deg"] <= 160.0 + 1e-9,
      "the angles lie within [20, 160] degrees")
check("dihedral angles 60.00 to 90.00 degrees" not in run.stdout,
      "the angles are not the lattice's alone (60 and 90 degrees)")
for label in sorted(report["tissues"], key=int):
    tissue = report["tissues"][label]
    row = "%8d %8d" % (int(label), tissue["tetrahedra"])
    check(row in run.stdout, "the example prints tissue %s with %d tets" % (label, tissue["tetrahedra"]))
check("Hausdorff distance %.3f mm" % report["hausdorff_mm"] in run.stdout,
      "the example prints the Hausdorff distance %.3f mm" % report["hausdorff_mm"])
check(report["hausdorff_mm"] < 1.5 * VOXEL, "the Hausdorff distance %.3f mm is under 1.5 voxels" % report["hausdorff_mm"])
check(report["hausdorff_mm"] < 0.5 * staircase["hausdorff_mm"],
      "the Hausdorff distance %.3f mm is under half the lattice's alone (%.3f mm)"
      % (report["hausdorff_mm"], staircase["hausdorff_mm"]))
check("ready for a solver" in run.stdout and "NOT ready" not in run.stdout, "the example says: ready for a solver")

if check(os.path.isfile(mesh_path), "the example wrote " + mesh_path):
    with open(mesh_path, "rb") as f:
        content = f.read()
    check(b'format="binary"' in content and b"<AppendedData" not in content,
          "the .vtu is inline binary, not appended")
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(mesh_path)
    reader.Update()
    mesh = reader.GetOutput()
    check(mesh.GetNumberOfCells() == report["tetrahedra"],
          "the .vtu reads back with %d cells (got %d)" % (report["tetrahedra"], mesh.GetNumberOfCells()))
    check(mesh.GetNumberOfPoints() == report["points"],
          "the .vtu reads back with %d points (got %d)" % (report["points"], mesh.GetNumberOfPoints()))
    labels = mesh.GetCellData().GetArray("Label")
    check(labels is not None and labels.GetRange() == (1.0, 3.0), "the .vtu has Label 1 to 3")
    check(mesh.GetCellData().GetArray("MinDihedralAngle") is not None, "the .vtu has the quality arrays")
    levels = mesh.GetCellData().GetArray("RefinementLevel")
    check(levels is not None and levels.GetRange()[1] > 0, "the .vtu is refined (RefinementLevel above 0)")
    moved = mesh.GetPointData().GetArray("Displacement")
    check(moved is not None and moved.GetMaxNorm() > 0.1 * VOXEL, "the .vtu is deformed (Displacement not zero)")

if check(os.path.isfile(picture_path), "the example wrote " + picture_path):
    png = vtkPNGReader()
    png.SetFileName(picture_path)
    png.Update()
    picture = png.GetOutput()
    dims = picture.GetDimensions()
    pixels = picture.GetPointData().GetScalars()
    check(dims[0] == 800 and dims[1] == 600, "the picture is 800 x 600 (got %d x %d)" % dims[:2])
    rgb_pixels = vtk_to_numpy(pixels)[:, :3].astype(int)
    samples = len(rgb_pixels)
    colours = len(np.unique(rgb_pixels, axis=0))
    background = int(np.all(rgb_pixels == 255, axis=1).sum())
    print("picture: %d colours in %d pixels, %.0f%% white" % (colours, samples, 100.0 * background / samples))
    check(colours > 50, "the picture has many colours (%d)" % colours)
    check(0.05 < background / samples < 0.95, "the picture is neither blank nor all mesh")
    # The legend's swatches are drawn unlit, in the map's own colours: a categorical map shows
    # each tissue's colour as a block of pixels; a continuous bar from 1 to 3 does not.
    for label, colour in zip((1, 2, 3), COLOURS):
        rgb = np.round(255 * np.array(colour)).astype(int)
        near = int((np.abs(rgb_pixels - rgb).max(axis=1) <= 3).sum())
        check(near >= 100, "the legend shows tissue %d in its colour %s (%d pixels)" % (label, rgb.tolist(), near))
check.finish()
