# pvpython, real images: `cbc3d IMAGE -o OUT --bcc-size 8 --fidelity 0 --iterations 0` writes a
# lattice whose every tet has 60 and 90 degree dihedral angles (to 0.01 degrees), that holds
# every tissue voxel centre (checked with VTK's probe filter), and keeps the image's labels.
# Skips (exit 77) when ../shared/data is absent.
import os
import subprocess
import sys
import tempfile

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkFiltersCore import vtkProbeFilter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, dihedral_angles, shared_data_or_skip  # noqa: E402

shared = shared_data_or_skip()
LoadPlugin(os.environ["CBC3D_PLUGIN"], remote=False, ns=globals())
cli = os.environ["CBC3D_CLI"]
check = Checks()


def tissue_voxel_centres(image, background):
    labels = vtk_to_numpy(image.GetPointData().GetScalars())
    dims = image.GetDimensions()
    flat = np.nonzero(~np.isin(labels, background))[0]
    ijk = np.stack([flat % dims[0], (flat // dims[0]) % dims[1], flat // (dims[0] * dims[1])], axis=1)
    direction = np.array([image.GetDirectionMatrix().GetElement(r, c) for r in range(3) for c in range(3)]).reshape(3, 3)
    world = np.array(image.GetOrigin()) + (ijk * np.array(image.GetSpacing())) @ direction.T
    return world, set(np.unique(labels[flat]).astype(int))


cases = [("cbc3d-brain.nii.gz", [0]), ("cbc3d-ventricles.nii.gz", [0]), ("cbc3d-nidus.nii.gz", [0]),
         ("nipype-tissue-labels.nii.gz", [0]), ("itk-t1-kmeans-labels.nii.gz", [1])]
with tempfile.TemporaryDirectory() as work:
    for name, background in cases:
        path = os.path.join(shared, name)
        out = os.path.join(work, name.replace(".nii.gz", ".vtu"))
        args = [cli, path, "-o", out, "--bcc-size", "8", "--fidelity", "0", "--iterations", "0", "--quiet"]
        for label in background:
            args += ["--background", str(label)]
        result = subprocess.run(args, capture_output=True, text=True, timeout=600)
        check(result.returncode == 0, "%s: cbc3d exits 0 %s" % (name, result.stderr.strip()))
        if result.returncode != 0:
            continue
        mesh = servermanager.Fetch(OpenDataFile(out))
        reader = OpenDataFile(path)
        image = servermanager.Fetch(reader)
        points = vtk_to_numpy(mesh.GetPoints().GetData())
        conn = vtk_to_numpy(mesh.GetCells().GetConnectivityArray()).reshape(-1, 4)
        angles = dihedral_angles(points[conn])
        check(np.abs(angles[:, :4] - 60).max() < 0.01 and np.abs(angles[:, 4:] - 90).max() < 0.01,
              "%s: %d tets, all dihedral angles 60 and 90 degrees" % (name, len(conn)))
        centres, tissue_labels = tissue_voxel_centres(image, background)
        mesh_labels = set(vtk_to_numpy(mesh.GetCellData().GetArray("Label")).astype(int))
        check(mesh_labels <= tissue_labels, "%s: mesh labels %s are image tissue labels %s" % (name, sorted(mesh_labels), sorted(tissue_labels)))
        cloud = vtkPolyData()
        pts = vtkPoints()
        pts.SetData(numpy_to_vtk(np.ascontiguousarray(centres), deep=True))
        cloud.SetPoints(pts)
        probe = vtkProbeFilter()
        probe.SetInputData(cloud)
        probe.SetSourceData(mesh)
        probe.Update()
        mask = vtk_to_numpy(probe.GetOutput().GetPointData().GetArray("vtkValidPointMask"))
        check(int(mask.sum()) == len(centres), "%s: %d of %d tissue voxel centres inside the mesh" % (name, int(mask.sum()), len(centres)))
        if name == "cbc3d-ventricles.nii.gz":
            check(mesh_labels == {128}, "ventricles keep label 128")

check.finish()
