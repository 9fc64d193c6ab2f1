# Plain python3: the independent topology checker (mesh_topology.py) gives the known answers on
# hand-made meshes and images, and its mesh and image halves agree with each other (and with
# scipy where it is installed) on random voxel sets meshed cube by cube.
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, kuhn_mesh, write_nifti  # noqa: E402
import mesh_topology as mt  # noqa: E402

check = Checks()


def expect(name, figures, **expected):
    got = {key: figures[key] for key in expected}
    check(got == expected, "%s: %s (expected %s)" % (name, got, expected))


# --- Hand-made tet meshes --------------------------------------------------------------------
P = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1],  # tet A
              [0, 0, 0], [1, 0, 0], [0, -1, 0], [0, 0, -1],  # B (its first two become A's)
              [-1, 0, 0], [0, -1, 0], [0, 0, -1]], dtype=float)  # C (hangs on A's point 0)
single = mt.mesh_report(P, [[0, 1, 2, 3]], [1])
expect("single tet", single[1], face_components=1, vertex_components=1, hinged=0, V=4, E=6, F=4,
       euler=2, nonmanifold_edges=0, nonmanifold_vertices=0)
edge = mt.mesh_report(P, [[0, 1, 2, 3], [0, 1, 6, 7]], [1, 1])
# Two tets on an edge: the edge is in 4 surface triangles; V 6, E 11, F 8.
expect("two tets on an edge", edge[1], face_components=2, vertex_components=1, hinged=1, euler=3,
       nonmanifold_edges=1, nonmanifold_vertices=0)
vertex = mt.mesh_report(P, [[0, 1, 2, 3], [0, 8, 9, 10]], [1, 1])
# Two tets on a vertex: two fans meet there; V 7, E 12, F 8.
expect("two tets on a vertex", vertex[1], face_components=2, vertex_components=1, hinged=1,
       euler=3, nonmanifold_edges=0, nonmanifold_vertices=1)
expect("two tets on a vertex, whole mesh", vertex["all"], hinged=1, nonmanifold_vertices=1)
apart = mt.mesh_report(P, [[0, 1, 2, 3], [8, 9, 10, 6]], [1, 2])
expect("two separate tets, two tissues: whole mesh", apart["all"], face_components=2,
       vertex_components=2, hinged=0, euler=4)
bowtie = mt.surface_topology([[0, 1, 2], [0, 3, 4]])
expect("two triangles on a vertex", bowtie, nonmanifold_vertices=1, nonmanifold_edges=0, euler=1)

# Solid torus: a ring of 8 cubes (3 x 3 x 1 less its centre), 48 tets.
ring = np.ones((3, 3, 1), dtype=int)
ring[1, 1, 0] = 0
torus = mt.mesh_report(*kuhn_mesh(ring))
expect("solid torus of tets", torus[1], tets=48, face_components=1, vertex_components=1, hinged=0,
       euler=0, nonmanifold_edges=0, nonmanifold_vertices=0)
# A solid ball (a 3 x 3 x 3 block) with two tissues in it: each tissue and the whole are balls.
block = np.ones((3, 3, 3), dtype=int)
block[:, :, 2] = 2
blocks = mt.mesh_report(*kuhn_mesh(block))
expect("block of two tissues, tissue 1", blocks[1], face_components=1, euler=2, hinged=0)
expect("block of two tissues, tissue 2", blocks[2], face_components=1, euler=2, hinged=0)
expect("block of two tissues, whole", blocks["all"], face_components=1, euler=2, hinged=0,
       nonmanifold_edges=0, nonmanifold_vertices=0)
# Cubes that touch along an edge only: a hinge, and a non-manifold edge.
diagonal = np.zeros((2, 2, 1), dtype=int)
diagonal[0, 0, 0] = diagonal[1, 1, 0] = 1
expect("two cubes on an edge", mt.mesh_report(*kuhn_mesh(diagonal))[1], face_components=2,
       vertex_components=1, hinged=1, nonmanifold_edges=1, euler=3)
corner = np.zeros((2, 2, 2), dtype=int)
corner[0, 0, 0] = corner[1, 1, 1] = 1
expect("two cubes on a corner", mt.mesh_report(*kuhn_mesh(corner))[1], face_components=2,
       vertex_components=1, hinged=1, nonmanifold_edges=0, nonmanifold_vertices=1, euler=3)

# --- Hand-made images ------------------------------------------------------------------------
one = np.zeros((3, 3, 3), dtype=int)
one[1, 1, 1] = 1
expect("one voxel", mt.image_report(one)[1], voxels=1, components=1, components_kept=0, euler=2)
expect("8-voxel ring", mt.image_report(ring)[1], voxels=8, components=1, components_kept=1, euler=0)
shell = np.ones((3, 3, 3), dtype=int)
shell[1, 1, 1] = 0
expect("hollow cube (a thick spherical shell)", mt.image_report(shell)[1], components=1, euler=4)
plate = np.ones((5, 3, 1), dtype=int)
plate[1, 1, 0] = plate[3, 1, 0] = 0
expect("plate with 2 holes, on the image border", mt.image_report(plate)[1], euler=-2)
expect("two voxels on an edge", mt.image_report(diagonal)[1], components=2, euler=3)
labels2 = np.zeros((4, 4, 4), dtype=int)
labels2[0:2] = 5
labels2[3] = 7
report2 = mt.image_report(labels2, background=[0])
expect("two slabs, label 5", report2[5], voxels=32, components=1, euler=2)
expect("two slabs, all tissues", report2["all"], components=2, components_kept=2, euler=4)

# --- NIfTI reading: the axis order and the data types ----------------------------------------
with tempfile.TemporaryDirectory() as work:
    values = np.arange(2 * 3 * 4).reshape(2, 3, 4)  # (nx, ny, nz)
    flat = [int(values[i, j, k]) for k in range(4) for j in range(3) for i in range(2)]  # x fastest
    for dtype, ext in (("int16", ".nii.gz"), ("float32", ".nii"), ("uint8", ".nii.gz")):
        path = os.path.join(work, "v" + ext)
        write_nifti(path, (2, 3, 4), flat, dtype=dtype)
        read = mt.read_nifti(path)
        check(read.shape == (2, 3, 4) and np.array_equal(read, values),
              "NIfTI %s%s read back as (nx, ny, nz) %s" % (dtype, ext, read.shape))

    # --- Reading a .vtu with string field data (what cbc3d writes and meshio cannot read) -----
    try:
        from vtkmodules.util.numpy_support import numpy_to_vtk
        from vtkmodules.vtkCommonCore import vtkPoints, vtkStringArray
        from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkUnstructuredGrid
        from vtkmodules.vtkIOLegacy import vtkUnstructuredGridWriter
        from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter
    except ImportError as error:
        check(False, "vtkmodules import under python3 (Debian's python3-paraview): %s" % error)
    else:
        points, tets, labels = kuhn_mesh(ring)
        grid = vtkUnstructuredGrid()
        vtk_points = vtkPoints()
        vtk_points.SetData(numpy_to_vtk(points, deep=True))
        grid.SetPoints(vtk_points)
        cells = vtkCellArray()
        offsets = np.arange(0, 4 * len(tets) + 1, 4, dtype=np.int64)
        cells.SetData(numpy_to_vtk(offsets, deep=True), numpy_to_vtk(tets.ravel().astype(np.int64), deep=True))
        grid.SetCells(10, cells)
        label_array = numpy_to_vtk((labels * 128).astype(np.int32), deep=True)
        label_array.SetName("Label")
        grid.GetCellData().AddArray(label_array)
        note = vtkStringArray()
        note.SetName("RefinementStopReason")
        note.InsertNextValue("fidelity reached")
        grid.GetFieldData().AddArray(note)
        for ext, Writer in ((".vtu", vtkXMLUnstructuredGridWriter), (".vtk", vtkUnstructuredGridWriter)):
            path = os.path.join(work, "ring" + ext)
            writer = Writer()
            writer.SetFileName(path)
            writer.SetInputData(grid)
            writer.Write()
            p, t, lab = mt.read_mesh(path)
            r = mt.mesh_report(p, t, lab)
            check(np.array_equal(t, tets) and set(r) == {128, "all"} and r[128]["euler"] == 0,
                  "read_mesh %s: %d tets, labels %s, Euler %d" % (ext, len(t), sorted(set(lab.tolist())), r[128]["euler"]))

# --- Random voxel sets: the mesh's figures against the image's -------------------------------
# A Kuhn mesh's tissue surface is the voxel-face surface with each square cut by a diagonal (one
# more edge and one more face each), so the Euler characteristics must agree; face components
# are 6-connected voxel components and vertex components 26-connected ones.
try:
    from scipy import ndimage
except ImportError:
    ndimage = None
    print("note: scipy not installed, the random sets are checked against the image half only")
rng = np.random.default_rng(20261201)
for trial in range(6):
    density = (0.25, 0.4, 0.55)[trial % 3]
    image = (rng.random((9, 8, 7)) < density).astype(int)
    image[image == 1] = rng.integers(1, 3, size=int(image.sum()))  # two tissues
    mesh = mt.mesh_report(*kuhn_mesh(image))
    voxels = mt.image_report(image)
    for label in (1, 2, "all"):
        mask = image > 0 if label == "all" else image == label
        figures = "trial %d tissue %s: Euler mesh %d image %d, face components %d image %d" % (
            trial, label, mesh[label]["euler"], voxels[label]["euler"], mesh[label]["face_components"],
            voxels[label]["components"])
        same = (mesh[label]["euler"] == voxels[label]["euler"]
                and mesh[label]["face_components"] == voxels[label]["components"])
        if ndimage is not None:
            six = ndimage.label(mask)[1]
            full = ndimage.label(mask, structure=np.ones((3, 3, 3)))[1]
            figures += ", scipy 6-connected %d, 26-connected %d, vertex components %d" % (
                six, full, mesh[label]["vertex_components"])
            same = same and six == voxels[label]["components"] and full == mesh[label]["vertex_components"]
        check(same, figures)

# --- Speed: a block of 120,000 voxels, two tissues, 720,000 tets ----------------------------
import time  # noqa: E402

big = np.ones((50, 40, 60), dtype=int)
big[:, :, 30:] = 2
start = time.time()
figures = mt.mesh_report(*kuhn_mesh(big))
seconds = time.time() - start
check(figures["all"]["tets"] == 720000 and figures["all"]["euler"] == 2 and figures[1]["euler"] == 2
      and figures["all"]["hinged"] == 0, "720,000-tet block: Euler %d, hinged %d"
      % (figures["all"]["euler"], figures["all"]["hinged"]))
check(seconds < 30, "720,000-tet block measured in %.1f s (under 30 s even on a busy machine)" % seconds)
check.finish()
