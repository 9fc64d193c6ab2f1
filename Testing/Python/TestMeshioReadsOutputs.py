# Plain python3: meshio (Debian's python3-meshio, the converter FE users reach for) reads every
# mesh file cbc3d writes, .vtu and .vtk, with the same points, tets and labels as VTK reads; the
# JSON report keeps the stop reasons the files leave out. Skips (77) without meshio.
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks  # noqa: E402
import mesh_topology as mt  # noqa: E402

try:
    import meshio
except ImportError:
    print("SKIP: meshio is not installed (Debian: python3-meshio)")
    sys.exit(77)

cli = os.environ["CBC3D_CLI"]
phantom = os.path.join(os.environ["CBC3D_SOURCE_DIR"], "Data", "nested_shells.vti")
check = Checks()
with tempfile.TemporaryDirectory() as work:
    for extension in (".vtu", ".vtk"):
        out = os.path.join(work, "mesh" + extension)
        report = os.path.join(work, "mesh%s.json" % extension)
        run = subprocess.run([cli, phantom, "-o", out, "--bcc-size", "4", "--quiet", "--report", report],
                             capture_output=True, text=True, timeout=300)
        if not check(run.returncode == 0, "%s: cbc3d exits 0 %s" % (extension, run.stderr.strip())):
            continue
        points, tets, labels = mt.read_mesh(out)  # VTK's reader
        try:
            mesh = meshio.read(out)
        except BaseException as error:  # meshio exits the process on some files (SystemExit)
            check(False, "%s: meshio reads it (%r)" % (extension, error))
            continue
        read = np.concatenate([c.data for c in mesh.cells if c.type == "tetra"])
        check(len(mesh.points) == len(points) and np.array_equal(read, tets),
              "%s: meshio reads %d points and %d tets, as VTK (%d, %d)"
              % (extension, len(mesh.points), len(read), len(points), len(tets)))
        meshio_labels = np.concatenate([d for d in mesh.cell_data.get("Label", [])]) if "Label" in mesh.cell_data else None
        check(meshio_labels is not None and np.array_equal(meshio_labels.ravel(), labels),
              "%s: the Label cell array comes through (%s tissues)"
              % (extension, sorted(set(np.unique(labels).tolist()))))
        p = np.asarray(mesh.points)[read]
        volumes = np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]))
        check((volumes > 0).all(), "%s: every tet positively oriented as meshio reads it" % extension)
        words = json.load(open(report))["refinement"]["stop_reason"]
        check(isinstance(words, str) and words != "", "%s: the report keeps the stop reason: %s" % (extension, words))
check.finish()
