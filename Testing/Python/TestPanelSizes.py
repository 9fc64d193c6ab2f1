# pvpython: the panels of CBC3D Image To Mesh, CBC3D BCC Lattice and CBC3D Refinement fill in
# the sizes that 0 stands for (lattice size, minimum edge length, boundary distance), computed
# from the input image's spacing; the run with the values shown gives the mesh of the run
# with 0. Known answers come from each phantom's spacing, read from its file's header here.
import math
import os
import re
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

plugin = os.environ["CBC3D_PLUGIN"]
source_dir = os.environ["CBC3D_SOURCE_DIR"]
output_dir = os.environ.get("CBC3D_TEST_OUTPUT", ".")
LoadPlugin(plugin, remote=False, ns=globals())
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks  # noqa: E402

check = Checks()


def close(value, expected):
    return math.isclose(value, expected, rel_tol=1e-12, abs_tol=1e-12)


def header_spacing(path):
    """The Spacing attribute of a .vti file, from its XML text (not through VTK)."""
    with open(path, "rb") as f:
        head = f.read(1000).decode("ascii", "replace")
    return [float(v) for v in re.search(r'Spacing="([^"]*)"', head).group(1).split()]


def expected_sizes(spacing):
    """The documented rules: 8 x the finest spacing, the cube root of the voxel volume, 3/8."""
    lattice = 8.0 * min(spacing)
    return lattice, (spacing[0] * spacing[1] * spacing[2]) ** (1.0 / 3.0), 0.375 * lattice


def check_image(name, known):
    path = os.path.join(source_dir, "Data", name)
    spacing = header_spacing(path)
    lattice, minimum, distance = expected_sizes(spacing)
    if known:
        check((lattice, minimum, distance) == known, "%s: expected %s from spacing %s" % (name, known, spacing))
    image = XMLImageDataReader(FileName=[path])  # not run: the sizes come from its information

    # Created as the GUI creates it: the panel's values are the domains' defaults.
    mesher = CBC3DImageToMesh(Input=image)
    shown = (mesher.LatticeSize, mesher.MinimumEdgeLength, mesher.BoundaryDistance)
    check(all(map(close, shown, (lattice, minimum, distance))),
          "%s: one-shot panel shows %s, expected %s" % (name, shown, (lattice, minimum, distance)))

    # What the panel's reset does after the input's information is updated.
    mesher.LatticeSize = 4.0
    mesher.UpdatePipelineInformation()
    mesher.GetProperty("LatticeSize").SMProperty.ResetToDomainDefaults()
    mesher.GetProperty("BoundaryDistance").SMProperty.ResetToDomainDefaults()
    check(close(mesher.LatticeSize, lattice), "%s: reset gives lattice size %g" % (name, mesher.LatticeSize))
    check(close(mesher.BoundaryDistance, 1.5),
          "%s: boundary distance of a 4 mm lattice: %g" % (name, mesher.BoundaryDistance))

    # The stage proxies: lattice edge, and refinement's sizes from the image and the lattice.
    stage = CBC3DBCCLattice(Input=image)
    check(close(stage.EdgeLength, lattice), "%s: lattice panel shows %g" % (name, stage.EdgeLength))
    refinement = CBC3DRefinement(Input=stage, Image=image)
    shown = (refinement.MinimumEdgeLength, refinement.BoundaryDistance)
    check(close(shown[0], minimum) and close(shown[1], distance),
          "%s: refinement panel shows %s, expected %s" % (name, shown, (minimum, distance)))
    stage.EdgeLength = 5.0
    refinement = CBC3DRefinement(Input=stage, Image=image)
    check(close(refinement.BoundaryDistance, 1.875),
          "%s: refinement of a 5 mm lattice shows %g" % (name, refinement.BoundaryDistance))
    # A mesh that is no CBC3D lattice: its longest edge is unknown before a run, 0 stays.
    other = CBC3DRefinement(Input=mesher, Image=image)
    check(other.BoundaryDistance == 0.0, "%s: refinement of another mesh keeps 0" % name)
    for proxy in (other, refinement, stage, mesher, image):
        Delete(proxy)


check_image("nested_shells.vti", (8.0, 1.0, 3.0))
check_image("oblique_ball.vti", None)  # 0.8 x 1 x 1.5 mm: 6.4 mm, cbrt(1.2) mm, 2.4 mm

# The run with the values shown is the run with 0, and uses them.
image = XMLImageDataReader(FileName=[os.path.join(source_dir, "Data", "nested_shells.vti")])
runs = []
for sizes in ("shown", (0.0, 0.0, 0.0)):
    mesher = CBC3DImageToMesh(Input=image)
    mesher.DeformationIterations = 0
    if sizes != "shown":
        mesher.LatticeSize, mesher.MinimumEdgeLength, mesher.BoundaryDistance = sizes
    mesh = servermanager.Fetch(mesher)
    fields = mesh.GetFieldData()
    runs.append((mesh.GetNumberOfCells(), mesh.GetNumberOfPoints(),
                 fields.GetArray("LatticeEdgeLength").GetValue(0),
                 fields.GetArray("RefinementBoundaryDistance").GetValue(0)))
check(runs[0][0] > 0 and runs[0][:2] == runs[1][:2], "same mesh with the values shown and with 0: %s" % runs)
check(runs[0][2] == 8.0 and close(runs[0][3], 3.0), "the run used 8 mm and 3 mm: %s" % (runs[0][2:],))

# An image narrower than 8 voxels: the automatic lattice size is larger than the image, and
# shown in the panel, it is accepted as it is when 0.
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
from vtkmodules.vtkCommonCore import vtkUnsignedCharArray

small = vtkImageData()
small.SetDimensions(6, 6, 6)
small.SetSpacing(0.5, 0.5, 0.5)
labels = vtkUnsignedCharArray()
labels.SetName("Labels")
for k in range(6):
    for j in range(6):
        for i in range(6):
            labels.InsertNextValue(1 if all(1 <= v <= 4 for v in (i, j, k)) else 0)
small.GetPointData().SetScalars(labels)
small_path = os.path.join(output_dir, "panel_sizes_small.vti")
writer = vtkXMLImageDataWriter()
writer.SetFileName(small_path)
writer.SetInputData(small)
writer.Write()
reader = XMLImageDataReader(FileName=[small_path])
tiny = CBC3DBCCLattice(Input=reader)
check(tiny.EdgeLength == 4.0, "small image: lattice panel shows %g (8 x 0.5 mm, over 3 mm across)" % tiny.EdgeLength)
cells = servermanager.Fetch(tiny).GetNumberOfCells()
check(cells > 0, "small image: the lattice of the size shown has %d tets" % cells)

check.finish()
