"""Meshes a label image with the one-shot filter and saves the mesh, as a user would under MPI:

    mpiexec -n N pvbatch mpi_mesh.py PLUGIN IMAGE OUTPUT... [Property=value ...]

Each OUTPUT (.msh, .xdmf, ... any extension of CBC3D Solver Mesh) is written once, whole, by
rank 0 from the ranks' pieces. A Property is one of CBC3D Image To Mesh's (LatticeSize,
Fidelity, DeformationIterations, RankHalo, ...); a list property takes its values separated by
commas (BackgroundLabels=0,1; TissueFidelity=2,0.9).
Exits 1 when the mesher or a writer fails.
"""
import sys

from paraview import servermanager
from paraview.simple import LoadPlugin, SaveData


def main():
    plugin, image = sys.argv[1:3]
    outputs = [a for a in sys.argv[3:] if "=" not in a]
    settings = [a for a in sys.argv[3:] if "=" in a]
    LoadPlugin(plugin, remote=False, ns=globals())
    reader = globals()["CBC3DNIfTIReader"](FileName=image)
    mesh = globals()["CBC3DImageToMesh"](Input=reader)
    for setting in settings:
        key, value = setting.split("=", 1)
        numbers = [float(v) if "." in v else int(v) for v in value.split(",")]
        setattr(mesh, key, numbers if "," in value or key == "BackgroundLabels" else numbers[0])
    mesh.UpdatePipeline()
    tets = mesh.GetDataInformation().GetNumberOfCells()
    if tets == 0:
        sys.exit(1)
    for output in outputs:
        SaveData(output, proxy=mesh)
    controller = servermanager.vtkProcessModule.GetProcessModule().GetGlobalController()
    ranks = controller.GetNumberOfProcesses() if controller else 1
    print("mpi_mesh: %d ranks, %d tets" % (ranks, tets))


if __name__ == "__main__":
    main()
