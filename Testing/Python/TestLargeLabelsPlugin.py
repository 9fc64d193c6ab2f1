"""pvpython: labels beyond 32 bits in ParaView (issue 16).

NIfTI-1 files of datatypes uint32, int64 and uint64 (written here) open with the plugin's
reader with their exact values; "CBC3D Image To Mesh" meshes them and its `Label` cell array and
the quality's `TissueLabel` field array hold those values; a background label beyond 32 bits
set through the BackgroundLabels property is not meshed; "CBC3D Tissue Surfaces" gives the
values in `BoundaryLabels`.

Environment: CBC3D_PLUGIN, CBC3D_TEST_OUTPUT. Exits 0 on success, 1 on failure.
"""
import os
import sys
import tempfile

import numpy as np

from paraview import servermanager
from paraview.simple import LoadPlugin, OpenDataFile
from vtkmodules.util.numpy_support import vtk_to_numpy

LoadPlugin(os.environ["CBC3D_PLUGIN"], remote=False, ns=globals())
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, write_nifti  # noqa: E402

check = Checks()
OUT = tempfile.mkdtemp(prefix="large-labels-plugin-", dir=os.environ.get("CBC3D_TEST_OUTPUT"))
DIMS = (10, 8, 8)


def phantom(dtype, background, low, high):
    labels = np.full(DIMS[::-1], background, dtype=dtype)
    labels[2:6, 2:6, 2:5] = low
    labels[2:6, 2:6, 5:8] = high
    return labels.ravel()


def values(array):
    return sorted(set(vtk_to_numpy(array).astype(np.int64).ravel().tolist()))


def mesh_case(dtype, background, low, high):
    name = "%s-%d-%d" % (dtype, low, high)
    path = os.path.join(OUT, name + ".nii")
    write_nifti(path, DIMS, [int(v) for v in phantom(dtype, background, low, high)], dtype)
    reader = OpenDataFile(path)
    image = servermanager.Fetch(reader)
    scalars = image.GetPointData().GetScalars()
    check(values(scalars) == sorted({background, low, high}), "%s: the reader gives %s" % (name, values(scalars)))
    mesher = CBC3DImageToMesh(Input=reader)  # noqa: F405 (from the plugin)
    mesher.LatticeSize = 2.5
    mesher.DeformationIterations = 1
    mesher.BackgroundLabels = [background]
    mesher.UpdatePipeline()
    mesh = servermanager.Fetch(mesher)
    labels = mesh.GetCellData().GetArray("Label")
    check(labels is not None and values(labels) == [low, high], "%s: Label holds %s" % (
        name, values(labels) if labels else None))
    tissues = mesh.GetFieldData().GetArray("TissueLabel")
    check(tissues is not None and values(tissues) == [low, high], "%s: TissueLabel holds the values" % name)
    surfaces = CBC3DTissueSurfaces(Input=mesher)  # noqa: F405
    surfaces.OutsideLabel = background
    surfaces.UpdatePipeline()
    sides = servermanager.Fetch(surfaces).GetCellData().GetArray("BoundaryLabels")
    check(sides is not None and values(sides) == sorted({background, low, high}),
          "%s: BoundaryLabels hold the values and the outside" % name)


mesh_case("uint32", 0, 7, 4000000000)
mesh_case("int64", 0, -5000000000, 5000000000)
mesh_case("uint64", 0, 3, 2**40)
mesh_case("int64", 6000000000, 1, 2)  # a background beyond 32 bits
check.finish()
