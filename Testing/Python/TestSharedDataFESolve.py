# Plain python3 with Debian's dolfinx 0.5.2 (python3-dolfinx-real): cbc3d's meshes of the brain,
# the nidus and the ventricles at the paper's settings carry a linear-elastic solve. E = 3000 Pa,
# nu = 0.45, the nodes in the lowest tenth of the z extent fixed, gravity as load (1000 kg/m^3),
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


def solve(points, cells):
    """(largest / median nodal displacement magnitude, relative residual, seconds, fixed dofs) of
    the gravity-loaded elastic solve on a P1 tet mesh, the lowest tenth (z) fixed."""
    start = time.time()
    domain = ufl.Mesh(ufl.VectorElement("Lagrange", "tetrahedron", 1))
    mesh = dolfinx.mesh.create_mesh(MPI.COMM_WORLD, np.asarray(cells, dtype=np.int64),
                                    np.asarray(points, dtype=np.float64), domain)
    z = mesh.geometry.x[:, 2]
    z_fixed = z.min() + 0.1 * (z.max() - z.min())
    fixed = []

    def lowest_tenth(V):
        fixed.append(dolfinx.fem.locate_dofs_geometrical(V, lambda x: x[2] <= z_fixed))
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
with tempfile.TemporaryDirectory() as work:
    for name in ("cbc3d-brain.nii.gz", "cbc3d-nidus.nii.gz", "cbc3d-ventricles.nii.gz"):
        out = os.path.join(work, name.replace(".nii.gz", ".vtu"))
        args = [cli, os.path.join(shared, name), "-o", out, "--background", "0", "--quiet"] + PAPER
        result = subprocess.run(args, capture_output=True, text=True, timeout=900)
        if not check(result.returncode == 0, "%s: cbc3d exits 0 %s" % (name, result.stderr.strip()[-400:])):
            continue
        points, tets, labels = mt.read_mesh(out)
        whole = mt.mesh_report(points, tets, labels)["all"]
        # Printed for the reading of a failure: hinges are what make the matrix singular.
        print("     %s: %d tets; whole mesh hinged %d, non-manifold edges %d, vertices %d"
              % (name, len(tets), whole["hinged"], whole["nonmanifold_edges"], whole["nonmanifold_vertices"]))
        judge("%s (paper settings)" % name, points, tets)
check.finish()
