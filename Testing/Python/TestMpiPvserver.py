# pvserver: pvpython connects to `mpiexec -n 2 pvserver`, loads the plugin on both sides and
# meshes the ventricles with the one-shot filter (Deformation Iterations 0). The client sees
# the whole mesh, spread over both ranks: as many tets as a serial run writes.
import os
import random
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, mpi_environment, mpi_programs_or_skip, run_mpi_mesh, shared_data_or_skip  # noqa: E402,E501

import meshio  # noqa: E402
from paraview.simple import Connect, Disconnect, LoadPlugin  # noqa: E402

SHARED = shared_data_or_skip()
MPIEXEC, PVSERVER = mpi_programs_or_skip("pvserver")
PLUGIN = os.environ["CBC3D_PLUGIN"]
IMAGE = os.path.join(SHARED, "cbc3d-ventricles.nii.gz")

check = Checks()
with tempfile.TemporaryDirectory() as work:
    serial = os.path.join(work, "serial.msh")
    run_mpi_mesh(1, IMAGE, [serial], ["DeformationIterations=0"], timeout=300)
    serial_tets = sum(len(b.data) for b in meshio.read(serial).cells if b.type == "tetra")
    port = random.randint(20000, 40000)
    server = subprocess.Popen([MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-n", "2", PVSERVER,
                               "--server-port=%d" % port], env=mpi_environment(), stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True)
    try:
        # pvserver says when it listens.
        deadline = time.time() + 120
        for line in server.stdout:
            if "Accepting connection" in line or time.time() > deadline:
                break
        Connect("localhost", port)
        LoadPlugin(PLUGIN, remote=True, ns=globals())
        LoadPlugin(PLUGIN, remote=False, ns=globals())
        reader = CBC3DNIfTIReader(FileName=IMAGE)  # noqa: F821 (the plugin's)
        mesh = CBC3DImageToMesh(Input=reader)  # noqa: F821
        mesh.DeformationIterations = 0
        mesh.UpdatePipeline()
        info = mesh.GetDataInformation()
        check(info.GetNumberOfCells() == serial_tets,
              "the client sees %d tets over 2 ranks, serial %d" % (info.GetNumberOfCells(), serial_tets))
        check("GlobalIds" in mesh.PointData.keys(), "the pieces carry GlobalIds")
        Disconnect()
    finally:
        server.terminate()
        try:
            server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            server.kill()
check.finish()
