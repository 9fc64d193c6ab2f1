# pvpython: with the CBC3D plugin loaded, File > Save Data (SaveData) writes the solver formats
# through the "CBC3D Solver Mesh" writer, byte for byte the files cbc3d writes for the same mesh
# (the .xdmf but for the name of its .h5, and that .h5 byte for byte) (whose contents
# TestMeshioReadsExports, TestGmshReadsMsh and TestDolfinxReadsXdmf check), and
# the "CBC3D Tissue Surfaces" filter gives every boundary and interface triangle with its
# BoundaryLabels and SurfaceId, counted per label pair with numpy from the mesh. ParaView's own
# Exodus II reader (Sandia's exodus library) reads the .exo's blocks and turns each side set's
# (element, side) pairs into triangles: they must be the expected faces, oriented out of the tet
# behind them.
import filecmp
import os
import subprocess
import sys
import tempfile

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

LoadPlugin(os.environ["CBC3D_PLUGIN"], remote=False, ns=globals())
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks  # noqa: E402
import export_expectations as ex  # noqa: E402

import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

check = Checks()
formats = ["mesh.msh", "mesh.inp", "mesh.mesh", "mesh.feb", "mesh.xdmf", "mesh.exo"]
with tempfile.TemporaryDirectory() as work:
    points, tets, labels = ex.mesh_phantom(work, formats)
    ex.mesh_phantom(work, ["mesh22.msh"], ["--msh-version", "2.2"])
    want = ex.expected(points, tets, labels)
    mesh = XMLUnstructuredGridReader(FileName=[os.path.join(work, "mesh.vtu")])
    mesh.UpdatePipeline()
    for name in formats:
        saved = os.path.join(work, "saved-" + name)
        SaveData(saved, proxy=mesh)
        if name.endswith(".xdmf"):
            # The .xdmf names its .h5 (saved-mesh.h5, mesh.h5); the .h5 files are the same bytes.
            with open(saved) as a, open(os.path.join(work, name)) as b:
                same = a.read().replace("saved-mesh.h5:", "mesh.h5:") == b.read()
            check(same and filecmp.cmp(os.path.join(work, "saved-mesh.h5"),
                                       os.path.join(work, "mesh.h5"), shallow=False),
                  "SaveData %s: the CBC3D writer's .xdmf and .h5 are cbc3d's (but the .h5's name)"
                  % name)
            continue
        check(os.path.exists(saved) and filecmp.cmp(saved, os.path.join(work, name), shallow=False),
              "SaveData %s: the CBC3D writer's file is cbc3d's, byte for byte" % name)
    saved = os.path.join(work, "saved-mesh22.msh")
    SaveData(saved, proxy=mesh, Gmsh22=1)
    check(os.path.exists(saved) and filecmp.cmp(saved, os.path.join(work, "mesh22.msh"), shallow=False),
          "SaveData .msh with Gmsh22 (the proxy property Gmsh 2.2): cbc3d's --msh-version 2.2 file")

    surfaces = servermanager.Fetch(CBC3DTissueSurfaces(Input=mesh))
    sides = vtk_to_numpy(surfaces.GetCellData().GetArray("BoundaryLabels"))
    ids = vtk_to_numpy(surfaces.GetCellData().GetArray("SurfaceId"))
    for pair, faces in want["pairs"].items():
        rows = np.all(sides == pair, axis=1)
        check(rows.sum() == len(faces) and np.all(ids[rows] == want["ids"][pair]),
              "CBC3D Tissue Surfaces: %s: %d triangles (expected %d), SurfaceId %d"
              % (want["names"][pair], rows.sum(), len(faces), want["ids"][pair]))
    check(surfaces.GetNumberOfCells() == sum(len(f) for f in want["pairs"].values()),
          "CBC3D Tissue Surfaces: %d triangles in all" % surfaces.GetNumberOfCells())

    reader = ExodusIIReader(FileName=[os.path.join(work, "mesh.exo")])
    reader.UpdatePipelineInformation()
    reader.ElementBlocks = list(reader.ElementBlocks.Available)
    reader.SideSetArrayStatus = list(reader.SideSetArrayStatus.Available)
    reader.UpdatePipeline()
    data = servermanager.Fetch(reader)
    parts = {}
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        parts[it.GetCurrentMetaData().Get(data.NAME())] = it.GetCurrentDataObject()
        it.GoToNextItem()
    check({k: parts[k].GetNumberOfCells() for k in parts if k.startswith("tissue_")}
          == {"tissue_%d" % k: v for k, v in want["tissues"].items()},
          "ExodusIIReader: a block per tissue with its tets: %s" % sorted(parts))
    for pair, faces in want["pairs"].items():
        part = parts.get(want["names"][pair])
        if not check(part is not None, "ExodusIIReader: the side set %s" % want["names"][pair]):
            continue
        # The reader's points are float32 copies: its GlobalNodeId (1-based) names the .vtu's point.
        node = vtk_to_numpy(part.GetPointData().GetArray("GlobalNodeId")).astype(np.int64) - 1
        cells = vtk_to_numpy(part.GetCells().GetConnectivityArray()).reshape(-1, 3)
        rows = node[cells].tolist()
        owner = dict(faces)
        same = sorted(tuple(sorted(r)) for r in rows) == sorted(owner)
        behind = ex.faces_behind_tets(points, tets, rows, [owner.get(tuple(sorted(r)), 0) for r in rows])
        check(same and behind == len(rows),
              "ExodusIIReader: %s: %d triangles (expected %d), the expected faces: %s, %d oriented "
              "out of the tet behind" % (want["names"][pair], len(rows), len(faces), same, behind))
check.finish()
