# Renders images/thin-shell-cavity.png: a spherical shell of 3.9 mm voxels, two voxels thick
# (a skull-like image, as in the topology phantoms test), meshed by cbc3d at the defaults and
# coloured by which way its surface faces (red: out, blue: into the cavity, white: the walls of a
# hole through the shell, where the cavity shows). Given a second, older cbc3d, it renders that
# one's mesh on the left:
#   xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython Documentation/MakeShellPicture.py \
#     build/bin/cbc3d [OLD_CBC3D]
import os
import subprocess
import sys
import tempfile

import numpy as np
from paraview.simple import *  # noqa: F401,F403

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "Testing", "Python"))
from cbc3d_testing import write_nifti  # noqa: E402
sys.path.insert(0, here)
from picture_views import white_view  # noqa: E402

clis = sys.argv[1:3]
work = tempfile.mkdtemp()
x, y, z = np.meshgrid(*[np.arange(64) + 0.5] * 3, indexing="ij")
d = np.sqrt((x - 32) ** 2 + (y - 32) ** 2 + (z - 32) ** 2)
shell = ((d > 25) & (d <= 27)).astype(np.int16)
image = os.path.join(work, "shell.nii")
write_nifti(image, shell.shape, shell.transpose(2, 1, 0).ravel().tolist(), dtype="int16", pixdim=(1.0, 3.9, 3.9, 3.9))

view = white_view([1400, 700])
centre = [125.0, 125.0, 125.0]  # mm: the shell's centre (64 voxels of 3.9 mm, origin 0)
for n, cli in enumerate(clis):  # the new mesh on the right, the old one 300 mm left of it
    mesh_path = os.path.join(work, "shell%d.vtu" % n)
    subprocess.run([cli, image, "-o", mesh_path, "--quiet"], check=True)
    mesh = XMLUnstructuredGridReader(FileName=[mesh_path])
    surface = GenerateSurfaceNormals(Input=ExtractSurface(Input=mesh))
    surface.Splitting = 0
    # The surface's facing: +1 outwards (the outer sphere), -1 inwards (the cavity's), about 0
    # on the walls of a hole through the shell.
    facing = Calculator(Input=surface)
    facing.AttributeType = "Point Data"
    facing.ResultArrayName = "Facing"
    facing.Function = "dot(Normals, norm(coords - (%g*iHat + %g*jHat + %g*kHat)))" % tuple(centre)
    moved = Transform(Input=facing)
    moved.Transform.Translate = [-300.0 * n, 0.0, 0.0]
    display = Show(moved, view)
    ColorBy(display, ("POINTS", "Facing"))
    lut = GetColorTransferFunction("Facing")
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(-1.0, 1.0)
HideScalarBarIfNotNeeded(GetColorTransferFunction("Facing"), view)
Render(view)  # the first render places the camera; placed again below
middle = 125.0 - 150.0 * (len(clis) - 1)
view.CameraPosition = [middle, 125.0 - 520.0, 125.0 + 120.0]
view.CameraFocalPoint = [middle, 125.0, 125.0]
view.CameraViewUp = [0, 0, 1]
view.CameraViewAngle = 36
Render(view)
SaveScreenshot(os.path.join(here, "images", "thin-shell-cavity.png"), view, ImageResolution=[1400, 700])
