# The ranks' pieces under `mpiexec -n 2 pvbatch --symmetric` (Testing/Python/mpi_pieces.py):
# - Ghost cells: asked for one layer of them, as a downstream filter asks, each rank adds to its
#   piece exactly the other rank's tets that touch it (share a corner, by GlobalIds), each
#   marked DUPLICATECELL in vtkGhostType, and keeps its own tets unmarked. The answer is worked
#   out here from the pieces without ghost cells. The mesh saved by ParaView's parallel writer
#   (.pvtu) reads back with every tet once, not counting the tets it marks as ghosts.
# - Slabs by tissue boundary (Balance Tissue): a ball in the top fifth of a tall NIfTI image.
#   Even slices leave the lower rank no tet (its slab holds no tissue, known by construction);
#   slabs by tissue give each rank at least a third of the tets.
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, mpi_environment, mpi_programs_or_skip, write_nifti  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import XMLPartitionedUnstructuredGridReader  # noqa: E402

MPIEXEC, PVBATCH = mpi_programs_or_skip("pvbatch")
SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SHELLS = os.path.join(SOURCE, "Data", "shells.nii.gz")
DRIVER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mpi_pieces.py")
DUPLICATECELL = 1

check = Checks()


def run_pieces(image, work, settings):
    """Each rank's report (mpi_pieces.py), or None where the run failed."""
    for rank in range(2):
        if os.path.exists(os.path.join(work, "rank-%d.json" % rank)):
            os.remove(os.path.join(work, "rank-%d.json" % rank))
    run = subprocess.run([MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-n", "2", PVBATCH, "--symmetric",
                          DRIVER, os.environ["CBC3D_PLUGIN"], image, work] + settings,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300,
                         env=mpi_environment())
    check(run.returncode == 0, "%s, %s: the 2-rank run ends well: %s"
          % (os.path.basename(image), " ".join(settings), run.stdout[-800:]))
    reports = []
    for rank in range(2):
        path = os.path.join(work, "rank-%d.json" % rank)
        if os.path.exists(path):
            with open(path) as f:
                reports.append(json.load(f))
    return reports if check(len(reports) == 2, "both ranks report their pieces") else None


def check_ghosts(reports, work):
    own = [{tuple(t) for t, ghost in r["levels_0"]} for r in reports]
    check(all(ghost == 0 for r in reports for _, ghost in r["levels_0"]),
          "without ghost cells asked, no tet is marked")
    check(all(own) and not own[0] & own[1], "each rank owns tets, none twice: %d and %d" % tuple(map(len, own)))
    for rank in range(2):
        with_ghosts = reports[rank]["levels_1"]
        kept = {tuple(t) for t, ghost in with_ghosts if ghost == 0}
        added = [tuple(t) for t, ghost in with_ghosts if ghost != 0]
        corners = {p for tet in own[rank] for p in tet}
        expected = {tet for tet in own[1 - rank] if corners.intersection(tet)}
        check(kept == own[rank], "rank %d keeps its own %d tets unmarked (%d)" % (rank, len(own[rank]), len(kept)))
        check(len(expected) > 0 and sorted(added) == sorted(expected),
              "rank %d adds the %d tets of the other rank that touch its own (%d added)"
              % (rank, len(expected), len(added)))
        check(all(ghost & DUPLICATECELL for _, ghost in with_ghosts if ghost != 0),
              "rank %d marks its ghost tets DUPLICATECELL" % rank)
    pvtu = os.path.join(work, "mesh.pvtu")
    if check(os.path.exists(pvtu), "ParaView's parallel writer saved mesh.pvtu"):
        readback = servermanager.Fetch(XMLPartitionedUnstructuredGridReader(FileName=[pvtu]))
        ghosts = readback.GetCellData().GetArray("vtkGhostType")
        cells = sum(1 for c in range(readback.GetNumberOfCells()) if not ghosts or ghosts.GetValue(c) == 0)
        check(cells == len(own[0]) + len(own[1]), "mesh.pvtu holds %d tets not marked as ghosts, the "
              "ranks own %d" % (cells, len(own[0]) + len(own[1])))


def ball_on_top(path):
    """40 x 40 x 150 voxels of 1 mm, a ball of radius 14 centred 20 slices below the top: tissue
    in slices 116 to 144 only."""
    nx, ny, nz = 40, 40, 150
    values = [1 if (i - 19.5) ** 2 + (j - 19.5) ** 2 + (k - 130) ** 2 <= 14 ** 2 else 0
              for k in range(nz) for j in range(ny) for i in range(nx)]
    write_nifti(path, (nx, ny, nz), values, dtype="uint8")


def owned_tets(reports):
    return [sum(1 for _, ghost in r["levels_0"] if ghost == 0) for r in reports]


with tempfile.TemporaryDirectory() as work:
    reports = run_pieces(SHELLS, work, ["LatticeSize=3.0"])
    if reports:
        check_ghosts(reports, work)
    ball = os.path.join(work, "ball.nii.gz")
    ball_on_top(ball)
    for balanced in (0, 1):
        reports = run_pieces(ball, work, ["LatticeSize=3.0", "DeformationIterations=0", "BalanceTissue=%d" % balanced])
        if reports:
            tets = owned_tets(reports)
            if balanced:
                check(min(tets) >= sum(tets) / 3.0, "slabs by tissue: the ranks own %d and %d tets" % tuple(tets))
            else:
                check(tets[0] == 0 and tets[1] > 0, "even slices: the ranks own %d and %d tets" % tuple(tets))
check.finish()
