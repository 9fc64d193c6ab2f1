# pvpython: every file format cbc3d writes reads back through ParaView's own readers, whole.
import json
import os
import subprocess
import sys
import tempfile

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

cli = os.environ["CBC3D_CLI"]
phantom = os.path.join(os.environ["CBC3D_SOURCE_DIR"], "Data", "touching_boxes.vti")
failures = []
with tempfile.TemporaryDirectory() as work:
    for extension in ("vtu", "vtk"):
        out = os.path.join(work, "boxes." + extension)
        report_path = os.path.join(work, extension + ".json")
        subprocess.run([cli, phantom, "-o", out, "--bcc-size", "1", "--quiet", "--report", report_path], check=True)
        report = json.load(open(report_path))
        mesh = servermanager.Fetch(OpenDataFile(out))
        labels = mesh.GetCellData().GetArray("Label")
        ok = (mesh.GetNumberOfCells() == report["tetrahedra"] and mesh.GetNumberOfPoints() == report["points"]
              and labels is not None and labels.GetRange() == (1.0, 2.0) and os.path.getsize(out) > 4096)
        print("%s %s: %d tets, %d points, %d bytes" % ("ok  " if ok else "FAIL", extension, mesh.GetNumberOfCells(),
                                                     mesh.GetNumberOfPoints(), os.path.getsize(out)))
        if not ok:
            failures.append(extension)
sys.exit(1 if failures else 0)
