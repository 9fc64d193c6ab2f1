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
# the rod's lower end (see below). Deformed too (the filter's default), on 2 and 3 ranks: every
# rank, the one without tissue too, ends; the mesh keeps its tets, conforms, keeps its angles
# within [20, 160] degrees, and each tissue of 1,000 voxels or more holds the serial run's
# volume within 0.5%, or one nearer its voxels' (1 mm voxels: one mm^3 each). (The serial run
# leaves the rod phantom's box 3.8% short of its voxels; the ranks come within 0.1%.)
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import (Checks, conforming, dihedral_angles, mpi_programs_or_skip, read_msh,  # noqa: E402
                           run_mpi_mesh, same_mesh, write_nifti)

mpi_programs_or_skip("pvbatch")
DEFORMED = ["LatticeSize=4.0", "RankHalo=2.0"]
SETTINGS = ["DeformationIterations=0"] + DEFORMED
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


def mesh_on_ranks(work, name, image, settings):
    """The meshes of 1, 2 and 3 ranks, by rank count, of those that ran."""
    runs = {}
    for ranks in (1, 2, 3):
        output = os.path.join(work, "%s-%d.msh" % (name, ranks))
        label = "%s, %d rank%s" % (name, ranks, "s" if ranks > 1 else "")
        try:
            result = run_mpi_mesh(ranks, image, [output], settings, timeout=180)
        except subprocess.TimeoutExpired:
            check(False, "%s: ended within 180 s" % label)
            continue
        if check(result.returncode == 0 and os.path.exists(output), "%s: ran and wrote .msh" % label):
            runs[ranks] = read_msh(output)
        else:
            print(result.stdout[-2000:])
    return runs


def check_deformed(name, labels, runs):
    """The deformed meshes against the serial one: tets, conformity, angles, volumes."""
    serial = runs.pop(1, None)
    voxels = {int(t): int(np.sum(labels == t)) for t in np.unique(labels) if t != 0}
    for ranks, mesh in runs.items():
        label = "%s, deformed, %d ranks" % (name, ranks)
        thrice, open_edges = conforming(mesh[1])
        angles = dihedral_angles(mesh[0][mesh[1]])
        check(thrice == 0 and open_edges == 0 and angles.min() >= 20.0 and angles.max() <= 160.0,
              "%s: conforming (%d, %d), angles %.2f-%.2f" % (label, thrice, open_edges, angles.min(), angles.max()))
        if serial is None:
            continue
        check(len(mesh[1]) == len(serial[1]), "%s: %d tets, serial %d" % (label, len(mesh[1]), len(serial[1])))
        for tissue, count in voxels.items():
            ours, theirs = tissue_volume(mesh, tissue), tissue_volume(serial, tissue)
            check(count < 1000 or abs(ours - theirs) <= 0.005 * theirs or abs(ours - count) < abs(theirs - count),
                  "%s: tissue %d (%d voxels) holds %.1f mm^3, serial %.1f" % (label, tissue, count, ours, theirs))


def tissue_volume(mesh, tissue):
    p = mesh[0][mesh[1][mesh[2] == tissue]]
    return float(np.abs(np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]))).sum() / 6)


check = Checks()
with tempfile.TemporaryDirectory() as work:
    for name, labels in phantoms().items():
        image = os.path.join(work, name + ".nii.gz")
        write_nifti(image, DIMS, labels.ravel().tolist())
        check_deformed(name, labels, mesh_on_ranks(work, name + "-deformed", image, DEFORMED))
        runs = mesh_on_ranks(work, name, image, SETTINGS)
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
