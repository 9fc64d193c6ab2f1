# Meshing over MPI ranks on phantoms made here, where the slabs see a tissue differently from the
# whole image: `mpiexec -n 2` and `-n 3` `pvbatch` give the serial mesh tet for tet.
#   - idle: the tissue lies at one end of a long image, so the last slab holds none and the one
#     before holds tissue in its halo alone. Such ranks make the same collective calls as the
#     others, with nothing to add; a rank that missed one would hang the run (it is cut off).
#     Inputs that stop the ranks with tissue (a fidelity for a tissue no slab holds) stop it too.
#   - rod: a rod one voxel thick runs from a ball in the upper slab into the lower one. The
#     lower rank's piece sees the rod without the ball: as a component of its own.
#   - cavity: a closed tube of background inside a tissue, from slab to slab. Each piece sees
#     the tube run out of its piece: the outside, for a piece on its own.
# The lattice is 4 mm and the halo 2 cubes, so that a piece ends well before the rod's ball or
# the tube's far end. The meshes are the serial run's tet for tet; their labels too, but for
# the rod's lower end (see below).
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, conforming, mpi_programs_or_skip, read_msh, run_mpi_mesh, same_mesh, write_nifti  # noqa: E402,E501

mpi_programs_or_skip("pvbatch")
SETTINGS = ["DeformationIterations=0", "LatticeSize=4.0", "RankHalo=2.0"]
DIMS = (32, 32, 96)  # x, y, z: the slabs cut z


def phantoms():
    z, y, x = np.mgrid[0:DIMS[2], 0:DIMS[1], 0:DIMS[0]]
    across = (x - 16) ** 2 + (y - 16) ** 2
    idle = np.zeros(z.shape, np.int16)
    idle[across + (z - 16) ** 2 <= 100] = 1
    idle[across + (z - 16) ** 2 <= 16] = 2
    rod = np.zeros(z.shape, np.int16)
    rod[4:92, 4:28, 4:28] = 1
    rod[across + (z - 78) ** 2 <= 81] = 2
    rod[20:70, 16, 16] = 2
    cavity = np.zeros(z.shape, np.int16)
    cavity[4:92, 4:28, 4:28] = 1
    cavity[(across <= 9) & (z >= 10) & (z < 86)] = 0
    return {"idle": idle, "rod": rod, "cavity": cavity}


def same_mesh_labels(serial, mesh):
    """Per tet of `mesh`, its index and label in the serial mesh (points matched by position)."""
    from scipy.spatial import cKDTree

    _, point = cKDTree(serial[0]).query(mesh[0])
    index = {tuple(t): i for i, t in enumerate(np.sort(serial[1], axis=1))}
    tets = np.array([index.get(tuple(t), -1) for t in np.sort(point[mesh[1]], axis=1)])
    return tets, np.where(tets >= 0, serial[2][tets], -1)


check = Checks()
with tempfile.TemporaryDirectory() as work:
    for name, labels in phantoms().items():
        image = os.path.join(work, name + ".nii.gz")
        write_nifti(image, DIMS, labels.ravel().tolist())
        runs = {}
        for ranks in (1, 2, 3):
            output = os.path.join(work, "%s-%d.msh" % (name, ranks))
            label = "%s, %d rank%s" % (name, ranks, "s" if ranks > 1 else "")
            try:
                result = run_mpi_mesh(ranks, image, [output], SETTINGS, timeout=180)
            except subprocess.TimeoutExpired:
                check(False, "%s: ended within 180 s" % label)
                continue
            if check(result.returncode == 0 and os.path.exists(output), "%s: ran and wrote .msh" % label):
                runs[ranks] = read_msh(output)
            else:
                print(result.stdout[-2000:])
        serial = runs.pop(1, None)
        for ranks, mesh in runs.items():
            label = "%s, %d ranks" % (name, ranks)
            thrice, open_edges = conforming(mesh[1])
            check(thrice == 0 and open_edges == 0,
                  "%s: conforming (%d faces in 3 tets, %d boundary edges not in 2 triangles)" % (label, thrice, open_edges))
            if serial is None:
                continue
            distance, foreign = same_mesh(serial, mesh)
            check(len(mesh[1]) == len(serial[1]) and foreign == 0 and distance < 1e-5,
                  "%s: the serial mesh (%d tets, serial %d, %d not serial, points within %.2g mm)" % (
                      label, len(mesh[1]), len(serial[1]), foreign, distance))
            # The labels: the ranks still decide alone which piece of a tissue in the mesh stands
            # for an image component (the sound labels' stray pieces), so the rod's lower end may
            # keep a tet the serial run gives to its neighbour: 1 tet in 1,000 at the most.
            _, match = same_mesh_labels(serial, mesh)
            differ = int(np.sum(match != mesh[2]))
            check(differ <= len(mesh[1]) // 1000,
                  "%s: %d tets labelled other than in the serial run (at most 1 in 1,000)" % (label, differ))
    # A fidelity asked for a tissue that no slab holds stops every rank, the one without tissue
    # too, with the reason and no file (it hung, before, waiting for the others).
    image, failed = os.path.join(work, "idle.nii.gz"), os.path.join(work, "failed.msh")
    try:
        result = run_mpi_mesh(3, image, [failed], SETTINGS + ["TissueFidelity=7,0.9"], timeout=180)
        check(result.returncode != 0 and "no voxel of tissue 7" in result.stdout and not os.path.exists(failed),
              "idle, 3 ranks, a fidelity for tissue 7: exit %d, the reason said, file %s" % (
                  result.returncode, "left" if os.path.exists(failed) else "absent"))
    except subprocess.TimeoutExpired:
        check(False, "idle, 3 ranks, a fidelity for tissue 7: ended within 180 s")
check.finish()
