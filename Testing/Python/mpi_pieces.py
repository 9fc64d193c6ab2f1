"""Under `mpiexec -n N pvbatch --symmetric` (every rank runs the script): meshes an image with the one-shot filter, asks each rank's
piece without ghost cells and then with one layer of them, as a downstream filter would, and
writes what each rank got to WORK/rank-R.json for TestMpiRankPieces.py:

    mpiexec -n N pvbatch --symmetric mpi_pieces.py PLUGIN IMAGE WORK [Property=value ...]

Each tet is listed by the GlobalIds of its corners. The mesh is then saved as WORK/mesh.pvtu
by ParaView's own parallel writer.
"""
import json
import os
import sys

from paraview import servermanager
from paraview.simple import LoadPlugin, SaveData


def tets_by_global_ids(mesh):
    """Each cell's corner GlobalIds, and its vtkGhostType value (0 where there is none)."""
    ids = mesh.GetPointData().GetGlobalIds()
    ghosts = mesh.GetCellData().GetArray("vtkGhostType")
    tets = []
    for c in range(mesh.GetNumberOfCells()):
        corners = mesh.GetCell(c).GetPointIds()
        tets.append([sorted(int(ids.GetValue(corners.GetId(k))) for k in range(corners.GetNumberOfIds())),
                     int(ghosts.GetValue(c)) if ghosts else 0])
    return tets


def main():
    plugin, image, work = sys.argv[1:4]
    LoadPlugin(plugin, remote=False, ns=globals())
    reader = globals()["CBC3DNIfTIReader"](FileName=image)
    mesh = globals()["CBC3DImageToMesh"](Input=reader)
    for setting in sys.argv[4:]:
        key, value = setting.split("=", 1)
        setattr(mesh, key, float(value) if "." in value else int(value))
    mesh.UpdatePipeline()
    controller = servermanager.vtkProcessModule.GetProcessModule().GetGlobalController()
    rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
    algorithm = mesh.GetClientSideObject()
    report = {"ranks": ranks}
    for levels in (0, 1):
        algorithm.UpdatePiece(rank, ranks, levels)
        piece = algorithm.GetOutputDataObject(0)
        report["levels_%d" % levels] = tets_by_global_ids(piece)
    with open(os.path.join(work, "rank-%d.json" % rank), "w") as out:
        json.dump(report, out)
    SaveData(os.path.join(work, "mesh.pvtu"), proxy=mesh)


if __name__ == "__main__":
    main()
