# pvpython: the quality filter's figures against an independent implementation: surface
# vertices and boundary voxels found with numpy, distances with VTK's own
# vtkHausdorffDistancePointSetFilter, angles with numpy. On a bundled phantom always, and on the
# shared three-tissue brain and k-means head when ../shared/data is there.
import os
import sys

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersModeling import vtkHausdorffDistancePointSetFilter

LoadPlugin(os.environ["CBC3D_PLUGIN"], remote=False, ns=globals())
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, dihedral_angles  # noqa: E402

check = Checks()
source = os.environ["CBC3D_SOURCE_DIR"]
shared = os.environ.get("CBC3D_SHARED_DATA", "")


def cloud(points):
    data = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=float), deep=True))
    data.SetPoints(pts)
    return data


def surface_vertices(conn, labels, label):
    """Vertices of the faces used by exactly one tet of the tissue."""
    tets = conn[labels == label]
    faces = np.concatenate([tets[:, [0, 1, 3]], tets[:, [1, 2, 3]], tets[:, [2, 0, 3]], tets[:, [0, 2, 1]]])
    faces = np.sort(faces, axis=1)
    unique, counts = np.unique(faces, axis=0, return_counts=True)
    return np.unique(unique[counts == 1])


def boundary_voxel_centres(image, label):
    """Centres of the tissue's voxels with a face-neighbour outside it (the border is outside)."""
    dims = image.GetDimensions()
    values = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(dims[2], dims[1], dims[0])
    inside = np.pad(values == label, 1, constant_values=False)
    core = inside[1:-1, 1:-1, 1:-1]
    interior = core.copy()
    for axis in range(3):
        for step in (1, -1):
            interior &= np.roll(inside, step, axis=axis)[1:-1, 1:-1, 1:-1]
    k, j, i = np.nonzero(core & ~interior)
    ijk = np.stack([i, j, k], axis=1).astype(float)
    direction = np.array([image.GetDirectionMatrix().GetElement(r, c) for r in range(3) for c in range(3)]).reshape(3, 3)
    return np.array(image.GetOrigin()) + (ijk * np.array(image.GetSpacing())) @ direction.T


def cross_check(name, image_path, edge, background):
    reader = OpenDataFile(image_path)
    lattice = CBC3DBCCLattice(Input=reader)
    lattice.EdgeLength = edge
    lattice.BackgroundLabels = background
    quality = CBC3DMeshQuality(Input=lattice, Image=reader)
    quality.BackgroundLabels = background
    quality.UpdatePipeline()
    mesh = servermanager.Fetch(quality)
    image = servermanager.Fetch(reader)
    fields = mesh.GetFieldData()
    points = vtk_to_numpy(mesh.GetPoints().GetData())
    conn = vtk_to_numpy(mesh.GetCells().GetConnectivityArray()).reshape(-1, 4)
    labels = vtk_to_numpy(mesh.GetCellData().GetArray("Label"))

    angles = dihedral_angles(points[conn])
    ours_min = vtk_to_numpy(mesh.GetCellData().GetArray("MinDihedralAngle"))
    ours_max = vtk_to_numpy(mesh.GetCellData().GetArray("MaxDihedralAngle"))
    check(np.allclose(ours_min, angles[:, 0], atol=1e-9) and np.allclose(ours_max, angles[:, 5], atol=1e-9),
          "%s: per-tet angles match numpy on %d tets" % (name, len(conn)))

    tissue_labels = [fields.GetArray("TissueLabel").GetValue(i) for i in range(fields.GetArray("TissueLabel").GetNumberOfTuples())]
    worst = 0.0
    for row, label in enumerate(tissue_labels):
        a = cloud(points[surface_vertices(conn, labels, label)])
        b = cloud(boundary_voxel_centres(image, label))
        vtk_hd = vtkHausdorffDistancePointSetFilter()
        vtk_hd.SetInputData(0, a)
        vtk_hd.SetInputData(1, b)
        vtk_hd.Update()
        hd = vtk_hd.GetHausdorffDistance()
        a_to_b, b_to_a = vtk_hd.GetRelativeDistance()
        ours = [fields.GetArray(n).GetValue(row) for n in ("TissueHausdorffDistance", "TissueMeshToImageDistance", "TissueImageToMeshDistance")]
        check(np.allclose(ours, [hd, a_to_b, b_to_a], atol=1e-9),
              "%s tissue %d: Hausdorff %.4f, one-sided %.4f / %.4f mm (VTK: %.4f, %.4f / %.4f)"
              % (name, label, ours[0], ours[1], ours[2], hd, a_to_b, b_to_a))
        distances = np.concatenate([vtk_to_numpy(vtk_hd.GetOutput(0).GetPointData().GetArray("Distance")),
                                    vtk_to_numpy(vtk_hd.GetOutput(1).GetPointData().GetArray("Distance"))])
        check(abs(fields.GetArray("TissueMeanSurfaceDistance").GetValue(row) - distances.mean()) < 1e-9,
              "%s tissue %d: mean distance %.4f mm" % (name, label, distances.mean()))
        worst = max(worst, hd)
    check(abs(fields.GetArray("HausdorffDistance").GetValue(0) - worst) < 1e-9,
          "%s: mesh Hausdorff distance is the largest over tissues (%.4f mm)" % (name, worst))


cross_check("nested shells", os.path.join(source, "Data", "nested_shells.vti"), 2.0, [0])
cross_check("oblique ball", os.path.join(source, "Data", "oblique_ball.vti"), 1.5, [0])
if os.path.isdir(shared):
    cross_check("nipype three tissues", os.path.join(shared, "nipype-tissue-labels.nii.gz"), 6.0, [0])
    cross_check("k-means head", os.path.join(shared, "itk-t1-kmeans-labels.nii.gz"), 8.0, [1])
else:
    print("shared images absent (%r): real-image cross-checks skipped" % shared)
check.finish()
