# pvpython: load the CBC3D plugin, build the lattice on a phantom through paraview.simple,
# and check the numbers against known answers.
import math
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

plugin = os.environ["CBC3D_PLUGIN"]
source_dir = os.environ["CBC3D_SOURCE_DIR"]
LoadPlugin(plugin, remote=False, ns=globals())
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, dihedral_angles  # noqa: E402

check = Checks()

# The oblique phantom: uint16 label 128, anisotropic spacing, a reflected direction matrix.
image = XMLImageDataReader(FileName=[os.path.join(source_dir, "Data", "oblique_ball.vti")])
image.UpdatePipeline()  # the label-array list needs the data information
lattice = CBC3DBCCLattice(Input=image)
lattice.EdgeLength = 2.0
lattice.UpdatePipeline()
mesh = servermanager.Fetch(lattice)

cells = mesh.GetNumberOfCells()
check(cells > 50, "lattice has %d tets" % cells)
labels = mesh.GetCellData().GetArray("Label")
check(labels is not None and labels.GetRange() == (128.0, 128.0), "Label keeps the value 128")

# Every tet is a BCC tet: angles 60 and 90 degrees, computed here from the points with numpy.
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

points = vtk_to_numpy(mesh.GetPoints().GetData())
conn = vtk_to_numpy(mesh.GetCells().GetConnectivityArray()).reshape(-1, 4)
p = points[conn]  # (tets, 4, 3)
volume = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p[:, 3] - p[:, 0]) / 6
check(bool((volume > 0).all()), "every tet positively oriented")
angles = dihedral_angles(p)
check(np.allclose(angles[:, :4], 60.0, atol=1e-6) and np.allclose(angles[:, 4:], 90.0, atol=1e-6),
      "dihedral angles are 60 and 90 degrees")

# The mesh lies in the image's world bounds (grown by one lattice edge for the outer tets).
info = image.GetDataInformation().GetBounds()
bounds = mesh.GetBounds()
for axis in range(3):
    check(bounds[2 * axis] >= info[2 * axis] - 2.0 - 1e-9 and bounds[2 * axis + 1] <= info[2 * axis + 1] + 2.0 + 1e-9,
          "mesh inside the image's world bounds on axis %d: %s vs %s" % (axis, bounds, info))

# Background labels through the repeatable property: 128 as background leaves no tissue,
# which the filter reports as an error and an empty output.
lattice.BackgroundLabels = [0, 128]
lattice.UpdatePipeline()
check(servermanager.Fetch(lattice).GetNumberOfCells() == 0, "no tets when every label is background")

# The proxy's object prints the settings we gave it.
lattice.BackgroundLabels = [0]
lattice.EdgeLength = 3.5
lattice.UpdatePipeline()
text = str(lattice.GetClientSideObject())
check("EdgeLength: 3.5" in text, "PrintSelf shows EdgeLength")

# A NIfTI file opened the way a user opens it: the plugin's reader places it in its world frame
# (an sform with a rotation), and the lattice lies inside the image's world bounds.
nifti = OpenDataFile(os.path.join(source_dir, "Data", "shells.nii.gz"))
check(nifti is not None and nifti.GetXMLName() == "CBC3DNIfTIReader", "OpenDataFile picks the CBC3D NIfTI reader")
# Created before the reader has run, so ParaView knows no array yet: the filter falls back to
# the image's active scalars.
shells = CBC3DBCCLattice(Input=nifti)
shells.EdgeLength = 2.0
shells.UpdatePipeline()
world = nifti.GetDataInformation().GetBounds()
mesh = servermanager.Fetch(shells)
bounds = mesh.GetBounds()
labels = mesh.GetCellData().GetArray("Label")
check(mesh.GetNumberOfCells() > 500, "shells lattice has %d tets" % mesh.GetNumberOfCells())
check(labels is not None and labels.GetRange() == (1.0, 3.0), "shells keep labels 1..3")
for axis in range(3):
    check(world[2 * axis] <= bounds[2 * axis] and bounds[2 * axis + 1] <= world[2 * axis + 1],
          "shells mesh inside the image's world bounds on axis %d: %s in %s" % (axis, bounds, world))

# The quality proxy reports the BCC angles in its field data.
quality = CBC3DMeshQuality(Input=shells)
quality.UpdatePipeline()
fields = servermanager.Fetch(quality).GetFieldData()
check(abs(fields.GetArray("MinDihedralAngle").GetValue(0) - 60) < 1e-6, "quality proxy: min 60")
check(abs(fields.GetArray("MaxDihedralAngle").GetValue(0) - 90) < 1e-6, "quality proxy: max 90")
check([fields.GetArray("TissueLabel").GetValue(i) for i in range(3)] == [1, 2, 3], "quality proxy: tissues 1 2 3")

# Refinement through its proxy: a finer, conforming mesh of the same tissues.
coarse = CBC3DBCCLattice(Input=nifti)
coarse.EdgeLength = 6.0
coarse.UpdatePipeline()
mesh = servermanager.Fetch(coarse)
refined = CBC3DRefinement(Input=coarse, Image=nifti)
refined.Fidelity = 0.99
refined.UpdatePipeline()
fine = servermanager.Fetch(refined)
fields = fine.GetFieldData()
check(fine.GetNumberOfCells() > mesh.GetNumberOfCells(), "refinement adds tets (%d -> %d)" % (mesh.GetNumberOfCells(), fine.GetNumberOfCells()))
check(fine.GetCellData().GetArray("RefinementLevel").GetRange()[1] >= 1, "some tets are refined")
check([fields.GetArray("FidelityLabel").GetValue(i) for i in range(3)] == [1, 2, 3], "fidelity per tissue 1 2 3")
check(all(0 < fields.GetArray(n).GetValue(i) <= 1 for n in ("FidelityF1", "FidelityF2") for i in range(3)), "F1, F2 in (0, 1]")
check("Fidelity: 0.99" in str(refined.GetClientSideObject()), "PrintSelf shows Fidelity")

# Deformation through its proxy; every Pattern entry reaches the C++ object by name.
deformed = CBC3DDeformation(Input=refined, Image=nifti)
for name in ("Vertex", "Edge", "Face", "None"):
    deformed.Pattern = name
    check("Pattern: " + name in str(deformed.GetClientSideObject()), "Pattern %s reaches the filter" % name)
deformed.Pattern = "Edge"
for name, printed in (("Voxel Face", "VoxelFace"), ("Voxel Centre", "VoxelCentre")):
    deformed.TargetPlacement = name
    check("TargetPlacement: " + printed in str(deformed.GetClientSideObject()),
          "TargetPlacement %s reaches the filter" % name)
check("KeepVolumes: on" in str(deformed.GetClientSideObject()), "KeepVolumes defaults to on")
deformed.KeepVolumes = 0
check("KeepVolumes: off" in str(deformed.GetClientSideObject()), "KeepVolumes off reaches the filter")
deformed.KeepVolumes = 1
deformed.Iterations = 3
deformed.UpdatePipeline()
moved = servermanager.Fetch(deformed)
check(moved.GetNumberOfCells() == fine.GetNumberOfCells(), "deformation keeps the tets")
check(moved.GetPointData().GetArray("Displacement").GetNumberOfComponents() == 3, "Displacement per point")
check(moved.GetFieldData().GetArray("DeformationIterations").GetValue(0) >= 1, "deformation iterated")

# The one-shot filter with its few default properties.
oneshot = CBC3DImageToMesh(Input=nifti)
oneshot.LatticeSize = 4.0
oneshot.DeformationIterations = 2
oneshot.UpdatePipeline()
final = servermanager.Fetch(oneshot)
fields = final.GetFieldData()
check(final.GetNumberOfCells() > 0 and fields.GetArray("InvertedTetCount").GetValue(0) == 0, "one-shot mesh, no inverted tet")
check(fields.GetArray("HausdorffDistance") is not None and fields.GetArray("FidelityF1") is not None, "one-shot figures")
check([p.GetXMLLabel() for p in [oneshot.GetProperty(n) for n in ("LatticeSize", "Fidelity", "Iterations")]] ==
      ["Lattice Size", "Fidelity", "Deformation Iterations"], "one-shot property labels")
check("TargetPlacement: 1" in str(oneshot.GetClientSideObject()), "one-shot TargetPlacement defaults to Voxel Face")
oneshot.TargetPlacement = "Voxel Centre"
check("KeepVolumes: on" in str(oneshot.GetClientSideObject()), "one-shot KeepVolumes defaults to on")
oneshot.KeepVolumes = 0
check("KeepVolumes: off" in str(oneshot.GetClientSideObject()), "one-shot KeepVolumes reaches the filter")
oneshot.KeepVolumes = 1
check("TargetPlacement: 0" in str(oneshot.GetClientSideObject()), "one-shot TargetPlacement reaches the filter")
oneshot.UpdatePipeline()
check(servermanager.Fetch(oneshot).GetFieldData().GetArray("InvertedTetCount").GetValue(0) == 0,
      "one-shot mesh with targets on the label boundary, no inverted tet")

check.finish()
