# Plain python3 with Debian's dolfinx 0.5.2 (python3-dolfinx-real): dolfinx reads the .xdmf
# cbc3d writes (read_mesh "mesh", read_meshtags "tissues" and "surfaces"), with, computed from
# the .vtu with numpy (export_expectations.py): the tets, the tets and the volume per tissue
# (integrated by dolfinx over each cell tag), the triangles and the area per surface (each facet
# tag, id as documented: boundaries by tissue, then interfaces). It then solves linear
# elasticity (E = 3000 Pa, nu = 0.45, gravity) with the displacement fixed on the facets tagged
# boundary_1, the outer surface: relative residual ||A u - b|| / ||b|| < 1e-8, zero displacement
# on the tagged facets and a non-zero one inside. Skips (77) without dolfinx.
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks  # noqa: E402
import export_expectations as ex  # noqa: E402

try:
    import dolfinx  # noqa: F401
except ImportError:
    # Debian puts dolfinx under PETSc's tree; its .pth file serves Debian's python3 only.
    sys.path.append(os.path.join(os.environ.get("PETSC_DIR") or "/usr/lib/petsc", "lib/python3/dist-packages"))
try:
    import dolfinx  # noqa: F811
    import dolfinx.fem.petsc
    import dolfinx.io
    import ufl
    from mpi4py import MPI
    from petsc4py import PETSc
except ImportError as error:
    print("SKIP: dolfinx not importable (%s); install python3-dolfinx-real" % error)
    sys.exit(77)
import logging  # noqa: E402

logging.disable(logging.INFO)  # FFCx logs each C compile of a form at INFO
E, NU, RHO_G = 3000.0e-6, 0.45, 1000.0e-12 * 9810.0  # N/mm^2, -, N/mm^3
check = Checks()


def integrate(form):
    return MPI.COMM_WORLD.allreduce(dolfinx.fem.assemble_scalar(dolfinx.fem.form(form)), op=MPI.SUM)


def solve(mesh, facets, fixed_id):
    """Relative residual, largest displacement on the fixed facets' nodes and overall."""
    V = dolfinx.fem.VectorFunctionSpace(mesh, ("Lagrange", 1))
    dofs = dolfinx.fem.locate_dofs_topological(V, 2, facets.find(fixed_id))
    bc = dolfinx.fem.dirichletbc(np.zeros(3, dtype=PETSc.ScalarType), dofs, V)
    mu, lam = E / (2 * (1 + NU)), E * NU / ((1 + NU) * (1 - 2 * NU))
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    eps = lambda w: ufl.sym(ufl.grad(w))  # noqa: E731
    a = ufl.inner(2 * mu * eps(u) + lam * ufl.tr(eps(u)) * ufl.Identity(3), eps(v)) * ufl.dx
    L = ufl.dot(dolfinx.fem.Constant(mesh, PETSc.ScalarType((0.0, 0.0, -RHO_G))), v) * ufl.dx
    uh = dolfinx.fem.petsc.LinearProblem(a, L, bcs=[bc], petsc_options={
        "ksp_type": "preonly", "pc_type": "lu", "pc_factor_mat_solver_type": "mumps"}).solve()
    a_form, L_form = dolfinx.fem.form(a), dolfinx.fem.form(L)
    A = dolfinx.fem.petsc.assemble_matrix(a_form, bcs=[bc])
    A.assemble()
    b = dolfinx.fem.petsc.assemble_vector(L_form)
    dolfinx.fem.petsc.apply_lifting(b, [a_form], bcs=[[bc]])
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    dolfinx.fem.petsc.set_bc(b, [bc])
    r = A.createVecLeft()
    A.mult(uh.vector, r)
    r.axpy(-1.0, b)
    values = uh.x.array.reshape(-1, 3)
    return r.norm() / b.norm(), np.abs(values[dofs]).max(), np.linalg.norm(values, axis=1).max()


with tempfile.TemporaryDirectory() as work:
    points, tets, labels = ex.mesh_phantom(work, ["mesh.xdmf"])
    want = ex.expected(points, tets, labels)
    # Inline XML data: open with ASCII encoding (the default, HDF5, looks for mesh.h5).
    with dolfinx.io.XDMFFile(MPI.COMM_WORLD, os.path.join(work, "mesh.xdmf"), "r",
                             encoding=dolfinx.io.XDMFFile.Encoding.ASCII) as xdmf:
        mesh = xdmf.read_mesh(name="mesh")
        mesh.topology.create_connectivity(2, 3)
        tissues = xdmf.read_meshtags(mesh, name="tissues")
        surfaces = xdmf.read_meshtags(mesh, name="surfaces")
    cells = mesh.topology.index_map(3).size_local
    check(cells == len(tets) and mesh.geometry.x.shape[0] == len(points),
          "dolfinx reads %d tets and %d points (the .vtu: %d, %d)" % (cells, mesh.geometry.x.shape[0], len(tets), len(points)))
    p = points[tets]
    tet_volumes = np.abs(np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]))) / 6
    dx = ufl.Measure("dx", domain=mesh, subdomain_data=tissues)
    for label, count in want["tissues"].items():
        tagged = int(np.sum(tissues.values == label))
        volume = integrate(dolfinx.fem.Constant(mesh, 1.0) * dx(label))
        expected_volume = tet_volumes[labels == label].sum()
        check(tagged == count and abs(volume - expected_volume) < 1e-9 * expected_volume,
              "cell tag tissue %d: %d tets (expected %d), volume %.6f mm^3 (expected %.6f)"
              % (label, tagged, count, volume, expected_volume))
    ds = ufl.Measure("ds", domain=mesh, subdomain_data=surfaces)
    dS = ufl.Measure("dS", domain=mesh, subdomain_data=surfaces)
    for pair, faces in want["pairs"].items():
        sid = want["ids"][pair]
        q = points[[f for f, _ in faces]]
        expected_area = 0.5 * np.linalg.norm(np.cross(q[:, 1] - q[:, 0], q[:, 2] - q[:, 0]), axis=1).sum()
        measure = ds(sid) if pair[1] == ex.OUTSIDE else dS(sid)
        area = integrate(dolfinx.fem.Constant(mesh, 1.0) * measure)
        tagged = int(np.sum(surfaces.values == sid))
        check(tagged == len(faces) and abs(area - expected_area) < 1e-9 * expected_area,
              "facet tag %d (%s): %d triangles (expected %d), area %.6f mm^2 (expected %.6f)"
              % (sid, want["names"][pair], tagged, len(faces), area, expected_area))
    fixed_id = want["ids"][(1, ex.OUTSIDE)]
    residual, on_fixed, largest = solve(mesh, surfaces, fixed_id)
    check(residual < 1e-8, "elasticity, boundary_1 (facet tag %d) fixed: relative residual %.3g (< 1e-8)"
          % (fixed_id, residual))
    check(on_fixed == 0.0 and largest > 0.0, "displacement 0 on the tagged facets, %.3g mm at most inside"
          % largest)
check.finish()
