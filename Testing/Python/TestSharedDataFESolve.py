# Plain python3 with Debian's dolfinx 0.5.2 (python3-dolfinx-real): cbc3d's meshes of the brain,
# the nidus and the ventricles at the paper's settings, and of the 3 mm head and the k-means head
# at tet budgets (--max-tets), carry a linear-elastic solve. E = 3000 Pa,
# nu = 0.45, the nodes in the lowest tenth of the z extent of each piece of the mesh fixed, gravity as load (1000 kg/m^3),
# in mm, N, tonne, s (so stresses in MPa); direct LU with MUMPS. A sound mesh gives a largest
# displacement a few times the median and a residual near machine precision; a tet that hangs on
# the rest by an edge or a vertex turns freely, the matrix is singular and both blow up.
# Checks per mesh: largest / median displacement magnitude < 100, ||A u - b|| / ||b|| < 1e-8.
# A box from dolfinx.mesh.create_box, passed through the same path, is the control that must
# pass. Skips (77) without dolfinx or without ../shared/data.
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy.sparse
import scipy.sparse.csgraph
import scipy.spatial

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, shared_data_or_skip  # noqa: E402
import mesh_topology as mt  # noqa: E402

import elasticity  # noqa: E402

elasticity.import_dolfinx()
from elasticity import MPI, dolfinx, ufl  # noqa: E402

RATIO_LIMIT = 100.0
RESIDUAL_LIMIT = 1e-8
PAPER = ["--bcc-size", "8", "--fidelity", "0.95", "--pattern", "edge", "--iterations", "5"]
check = Checks()


def anchored_points(points, cells):
    """The points in the lowest tenth (z) of their piece of the mesh (pieces joined through a
    vertex are one), and the four lowest of each piece: every piece is held, so that only a
    hinge, not a separate piece of tissue (the k-means head has some), can turn freely."""
    points = np.asarray(points, dtype=np.float64)
    cells = np.asarray(cells, dtype=np.int64)
    rows = np.repeat(cells, 4, axis=1).ravel()
    cols = np.tile(cells, (1, 4)).ravel()
    graph = scipy.sparse.coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(len(points), len(points)))
    count, piece = scipy.sparse.csgraph.connected_components(graph, directed=False)
    z = points[:, 2]
    low = np.full(count, np.inf)
    high = np.full(count, -np.inf)
    np.minimum.at(low, piece, z)
    np.maximum.at(high, piece, z)
    used = np.zeros(len(points), dtype=bool)
    used[cells.ravel()] = True
    anchored = used & (z <= low[piece] + 0.1 * (high[piece] - low[piece]))
    # A small piece (a speck of tissue, a few tets) has one or two points there: its four lowest
    # points hold it against turning too.
    order = np.lexsort((z, piece))
    order = order[used[order]]
    first = np.searchsorted(piece[order], np.arange(count))
    rank = np.arange(len(order)) - first[piece[order]]
    anchored[order[rank < 4]] = True
    return points[anchored]


def solve(points, cells):
    """(largest / median nodal displacement magnitude, relative residual, seconds, fixed dofs) of
    the gravity-loaded elastic solve on a P1 tet mesh, the lowest tenth (z) of each piece fixed."""
    start = time.time()
    domain = ufl.Mesh(ufl.VectorElement("Lagrange", "tetrahedron", 1))
    mesh = dolfinx.mesh.create_mesh(MPI.COMM_WORLD, np.asarray(cells, dtype=np.int64),
                                    np.asarray(points, dtype=np.float64), domain)
    anchors = scipy.spatial.cKDTree(anchored_points(points, cells))
    fixed = []

    def lowest_tenth(V):
        fixed.append(dolfinx.fem.locate_dofs_geometrical(
            V, lambda x: anchors.query(x.T, distance_upper_bound=1e-9)[0] < 1e-9))
        return fixed[0]

    displacement, residual = elasticity.solve(mesh, lowest_tenth)
    magnitude = np.linalg.norm(displacement, axis=1)
    ratio = magnitude.max() / np.median(magnitude) if np.median(magnitude) > 0 else np.inf
    return ratio, residual, time.time() - start, len(fixed[0])


def judge(name, points, cells):
    try:
        ratio, residual, seconds, fixed = solve(points, cells)
    except Exception as error:  # a singular matrix may stop MUMPS: that fails the mesh too
        check(False, "%s: the solve raised %s: %s" % (name, type(error).__name__, error))
        return
    check(np.isfinite(ratio) and ratio < RATIO_LIMIT,
          "%s: %d tets, %d fixed nodes, largest / median displacement %.4g (< %g), %.1f s"
          % (name, len(cells), fixed, ratio, RATIO_LIMIT, seconds))
    check(np.isfinite(residual) and residual < RESIDUAL_LIMIT,
          "%s: relative residual ||A u - b|| / ||b|| %.3g (< %g)" % (name, residual, RESIDUAL_LIMIT))


# Control: a 100 x 80 x 60 mm box, 10 x 8 x 6 cubes of 6 tets each, sound by construction.
box = dolfinx.mesh.create_box(MPI.COMM_WORLD, [np.zeros(3), np.array([100.0, 80.0, 60.0])], [10, 8, 6],
                              dolfinx.mesh.CellType.tetrahedron)
box_cells = box.geometry.dofmap.array.reshape(-1, 4)
judge("control: dolfinx box", box.geometry.x.copy(), box_cells)
# Controls the other way: the box with one more tet on its top face that shares only a vertex,
# or only an edge, with it. Each is a hinge: the solve must fail the limits, or the test could not
# see hinges. (The free points are placed off any symmetry, so that gravity drives the free
# rotation; a mode the load does not drive would leave the solve looking sound.)
x = box.geometry.x.copy()
top = np.nonzero(np.isclose(x[:, 2], 60.0))[0]
node = {tuple(np.round(x[i])): i for i in top}
for kind, shared_nodes, free in (("a vertex", [(50, 40, 60)], [(50, 40, 75), (40, 50, 75), (45, 35, 80)]),
                                 ("an edge", [(50, 40, 60), (60, 40, 60)], [(55, 45, 75), (52, 30, 68)])):
    points = np.vstack([x, np.array(free, dtype=float)])
    tet = [node[p] for p in shared_nodes] + list(range(len(x), len(points)))
    cells = np.vstack([box_cells, [tet]])
    whole = mt.mesh_report(points, cells, np.ones(len(cells), dtype=int))["all"]
    try:
        ratio, residual, seconds, fixed = solve(points, cells)
        caught = not (ratio < RATIO_LIMIT and residual < RESIDUAL_LIMIT)
        figures = "largest / median displacement %.4g, relative residual %.3g" % (ratio, residual)
    except Exception as error:
        caught, figures = True, "the solve raised %s" % type(error).__name__
    check(caught and whole["hinged"] == 1, "control: box and a tet hinged on %s (hinged %d): %s, "
          "beyond the limits" % (kind, whole["hinged"], figures))
if check.failures:
    check.finish()  # a control that fails says the test itself is wrong

shared = shared_data_or_skip()
cli = os.environ["CBC3D_CLI"]
# The paper's settings, and meshes of a size the user asked for (--max-tets).
CASES = [(name, "paper settings", ["--background", "0"] + PAPER)
         for name in ("cbc3d-brain.nii.gz", "cbc3d-nidus.nii.gz", "cbc3d-ventricles.nii.gz")]
CASES += [("nipype-tissue-labels.nii.gz", "--max-tets %d" % n, ["--max-tets", str(n)]) for n in (20000, 50000, 100000)]
CASES += [("itk-t1-kmeans-labels.nii.gz", "--max-tets 100000, background 1",
           ["--max-tets", "100000", "--background", "1"])]
with tempfile.TemporaryDirectory() as work:
    for name, settings, options in CASES:
        out = os.path.join(work, name.replace(".nii.gz", ".vtu"))
        args = [cli, os.path.join(shared, name), "-o", out, "--quiet"] + options
        result = subprocess.run(args, capture_output=True, text=True, timeout=900)
        if not check(result.returncode == 0, "%s: cbc3d exits 0 %s" % (name, result.stderr.strip()[-400:])):
            continue
        points, tets, labels = mt.read_mesh(out)
        whole = mt.mesh_report(points, tets, labels)["all"]
        # Printed for the reading of a failure: hinges are what make the matrix singular.
        print("     %s: %d tets; whole mesh hinged %d, non-manifold edges %d, vertices %d"
              % (name, len(tets), whole["hinged"], whole["nonmanifold_edges"], whole["nonmanifold_vertices"]))
        judge("%s (%s)" % (name, settings), points, tets)
check.finish()
