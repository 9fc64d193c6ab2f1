# Plain python3 with Debian's dolfinx 0.5.2 (python3-dolfinx-real): dolfinx, opening the file
# as a FEniCSx user does (XDMFFile's default encoding, HDF5), reads the .xdmf and the .h5 beside
# it that cbc3d writes (read_mesh "mesh", read_meshtags "tissues" and "surfaces"), with, computed from
# the .vtu with numpy (export_expectations.py): the tets, the tets and the volume per tissue
# (integrated by dolfinx over each cell tag), the triangles and the area per surface (each facet
# tag, id as documented: boundaries by tissue, then interfaces). It then solves linear
# elasticity (elasticity.py: E = 3000 Pa, nu = 0.45, gravity) with the displacement fixed on
# the facets tagged boundary_1, the outer surface: relative residual ||A u - b|| / ||b|| < 1e-8, zero displacement
# on the tagged facets and a non-zero one inside. Skips (77) without dolfinx.
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks  # noqa: E402
import export_expectations as ex  # noqa: E402

import elasticity  # noqa: E402

elasticity.import_dolfinx()
from elasticity import MPI, dolfinx, ufl  # noqa: E402

check = Checks()


def integrate(form):
    return MPI.COMM_WORLD.allreduce(dolfinx.fem.assemble_scalar(dolfinx.fem.form(form)), op=MPI.SUM)


with tempfile.TemporaryDirectory() as work:
    points, tets, labels = ex.mesh_phantom(work, ["mesh.xdmf"])
    want = ex.expected(points, tets, labels)
    check(os.path.isfile(os.path.join(work, "mesh.h5")), "mesh.h5 beside mesh.xdmf")
    # The default encoding (HDF5): the data items name mesh.h5.
    with dolfinx.io.XDMFFile(MPI.COMM_WORLD, os.path.join(work, "mesh.xdmf"), "r") as xdmf:
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
    fixed = []

    def tagged_facets(V):
        fixed.append(dolfinx.fem.locate_dofs_topological(V, 2, surfaces.find(fixed_id)))
        return fixed[0]

    displacement, residual = elasticity.solve(mesh, tagged_facets)
    on_fixed = np.abs(displacement[fixed[0]]).max()
    largest = np.linalg.norm(displacement, axis=1).max()
    check(residual < 1e-8, "elasticity, boundary_1 (facet tag %d) fixed: relative residual %.3g (< 1e-8)"
          % (fixed_id, residual))
    check(on_fixed == 0.0 and largest > 0.0, "displacement 0 on the tagged facets, %.3g mm at most inside"
          % largest)
check.finish()
