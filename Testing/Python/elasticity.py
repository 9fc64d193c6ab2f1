"""Linear elasticity with dolfinx 0.5 (Debian's python3-dolfinx-real), shared by the tests that
put cbc3d's meshes through a solver: E = 3000 Pa, nu = 0.45, gravity (1000 kg/m^3) as load, in
mm, N, tonne, s; direct LU with MUMPS. `import_dolfinx()` first: it exits 77 (skipped) with a
message where dolfinx cannot be imported."""
import logging
import os
import sys

import numpy as np

E = 3000.0e-6  # 3000 Pa in N/mm^2
NU = 0.45
RHO_G = 1000.0e-12 * 9810.0  # 1000 kg/m^3 = 1e-9 t/mm^3, times g = 9810 mm/s^2: N/mm^3


def import_dolfinx():
    """Imports dolfinx, ufl, MPI and PETSc into this module, or exits 77."""
    try:
        import dolfinx  # noqa: F401
    except ImportError:
        # Debian installs dolfinx and petsc4py under PETSc's own tree; its petsc4py.pth adds that
        # folder to the dist-packages of Debian's python3 only; add it here for other set-ups.
        sys.path.append(os.path.join(os.environ.get("PETSC_DIR") or "/usr/lib/petsc", "lib/python3/dist-packages"))
    try:
        global dolfinx, ufl, MPI, PETSc
        import dolfinx  # noqa: F811
        import dolfinx.fem.petsc
        import dolfinx.io
        import ufl
        from mpi4py import MPI
        from petsc4py import PETSc
    except ImportError as error:
        print("SKIP: dolfinx not importable (%s); install python3-dolfinx-real" % error)
        sys.exit(77)
    logging.disable(logging.INFO)  # FFCx logs each C compile of a form at INFO


def solve(mesh, fixed_dofs):
    """(nodal displacements (n, 3), relative residual ||A u - b|| / ||b||) of the gravity-loaded
    solve on P1 vector elements of `mesh`, the dofs `fixed_dofs(V)` held at zero."""
    V = dolfinx.fem.VectorFunctionSpace(mesh, ("Lagrange", 1))
    bc = dolfinx.fem.dirichletbc(np.zeros(3, dtype=PETSc.ScalarType), fixed_dofs(V), V)
    mu = E / (2 * (1 + NU))
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)

    def eps(w):
        return ufl.sym(ufl.grad(w))

    def sigma(w):
        return 2 * mu * eps(w) + lam * ufl.tr(eps(w)) * ufl.Identity(3)

    f = dolfinx.fem.Constant(mesh, PETSc.ScalarType((0.0, 0.0, -RHO_G)))
    a = ufl.inner(sigma(u), eps(v)) * ufl.dx
    L = ufl.dot(f, v) * ufl.dx
    problem = dolfinx.fem.petsc.LinearProblem(a, L, bcs=[bc], petsc_options={
        "ksp_type": "preonly", "pc_type": "lu", "pc_factor_mat_solver_type": "mumps"})
    uh = problem.solve()
    # The residual with a matrix and vector assembled again, with the same boundary conditions.
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
    return uh.x.array.reshape(-1, 3).copy(), r.norm() / b.norm()
