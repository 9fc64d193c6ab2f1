# pvpython: the example Documentation/Examples/mesh_nifti.py, run as a user runs it
# (`xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython mesh_nifti.py PLUGIN IMAGE OUT.vtu
# SHOT.png --edge-length 2`) on
# Data/shells.nii.gz. Checks: exit 0; the printed figures; the .vtu reads back with the tets,
# points and labels the cbc3d command gives for the same image and lattice size; the PNG is a
# real picture (several colours, not one flat tone). Skips (77) without xvfb-run or when
# Xvfb cannot start.
import json
import os
import shutil
import subprocess
import sys

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
           picture_path, "--edge-length", "2"]
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

# The same image and lattice size through the command line (lattice alone: no refinement, no
# deformation, as in the example), for the expected figures.
report_path = os.path.join(work, "cli.json")
subprocess.run([cli, image, "-o", os.path.join(work, "cli.vtu"), "--bcc-size", "2", "--fidelity", "0",
                "--iterations", "0", "--quiet", "--report", report_path], check=True)
report = json.load(open(report_path))

check("tetrahedra %d, points %d" % (report["tetrahedra"], report["points"]) in run.stdout,
      "the example prints %d tetrahedra and %d points" % (report["tetrahedra"], report["points"]))
check("dihedral angles 60.00 to 90.00 degrees" in run.stdout, "the example prints the angles 60 and 90")
for label in sorted(report["tissues"], key=int):
    tissue = report["tissues"][label]
    row = "%8d %8d" % (int(label), tissue["tetrahedra"])
    check(row in run.stdout, "the example prints tissue %s with %d tets" % (label, tissue["tetrahedra"]))
check("%.3f mm" % report["hausdorff_mm"] in run.stdout,
      "the example prints the Hausdorff distance %.3f mm" % report["hausdorff_mm"])

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

if check(os.path.isfile(picture_path), "the example wrote " + picture_path):
    png = vtkPNGReader()
    png.SetFileName(picture_path)
    png.Update()
    picture = png.GetOutput()
    dims = picture.GetDimensions()
    pixels = picture.GetPointData().GetScalars()
    check(dims[0] == 800 and dims[1] == 600, "the picture is 800 x 600 (got %d x %d)" % dims[:2])
    components = pixels.GetNumberOfComponents()
    colours = set()
    background = 0
    for i in range(0, pixels.GetNumberOfTuples(), 7):
        colour = tuple(int(pixels.GetComponent(i, c)) for c in range(min(components, 3)))
        colours.add(colour)
        background += colour == (255, 255, 255)
    samples = (pixels.GetNumberOfTuples() + 6) // 7
    print("picture: %d colours in %d samples, %.0f%% white" % (len(colours), samples, 100.0 * background / samples))
    check(len(colours) > 50, "the picture has many colours (%d)" % len(colours))
    check(0.05 < background / samples < 0.95, "the picture is neither blank nor all mesh")
check.finish()
