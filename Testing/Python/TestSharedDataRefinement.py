# pvpython, real images: `cbc3d IMAGE -o OUT --bcc-size 8 --fidelity 0.95 --iterations 0` gives
# a refined mesh whose dihedral angles all lie in [30, 116.57] degrees (to 0.05), with no
# hanging vertex, every face shared by at most two tets, F1 and F2 reported per tissue, and
# every 6-connected tissue component of 8 voxels or more kept. Skips (77) without ../shared/data.
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, dihedral_angles, shared_data_or_skip  # noqa: E402

shared = shared_data_or_skip()
cli = os.environ["CBC3D_CLI"]
check = Checks()
LARGEST = np.degrees(np.arccos(-1 / np.sqrt(5)))  # 116.565: the green split of a face


def conformity(points, conn):
    """(faces used more than twice, hanging vertices): a vertex at the midpoint of an edge."""
    faces = np.sort(np.concatenate([conn[:, [0, 1, 3]], conn[:, [1, 2, 3]], conn[:, [2, 0, 3]], conn[:, [0, 2, 1]]]), axis=1)
    _, counts = np.unique(faces, axis=0, return_counts=True)
    edges = np.unique(np.sort(np.concatenate([conn[:, [a, b]] for a, b in ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))]), axis=1), axis=0)
    midpoints = 0.5 * (points[edges[:, 0]] + points[edges[:, 1]])
    vertex_keys = set(map(bytes, np.ascontiguousarray(points)))
    hanging = sum(1 for m in np.ascontiguousarray(midpoints) if bytes(m) in vertex_keys)
    return int((counts > 2).sum()), hanging


cases = [("cbc3d-brain.nii.gz", [0]), ("cbc3d-nidus.nii.gz", [0]), ("cbc3d-ventricles.nii.gz", [0]),
         ("nipype-tissue-labels.nii.gz", [0]), ("itk-t1-kmeans-labels.nii.gz", [1])]
with tempfile.TemporaryDirectory() as work:
    for name, background in cases:
        out = os.path.join(work, name.replace(".nii.gz", ".vtu"))
        report_path = out + ".json"
        args = [cli, os.path.join(shared, name), "-o", out, "--bcc-size", "8", "--fidelity", "0.95",
                "--iterations", "0", "--quiet", "--report", report_path]
        for label in background:
            args += ["--background", str(label)]
        result = subprocess.run(args, capture_output=True, text=True, timeout=900)
        if not check(result.returncode == 0, "%s: cbc3d exits 0 %s" % (name, result.stderr.strip())):
            continue
        report = json.load(open(report_path))
        mesh = servermanager.Fetch(OpenDataFile(out))
        points = vtk_to_numpy(mesh.GetPoints().GetData())
        conn = vtk_to_numpy(mesh.GetCells().GetConnectivityArray()).reshape(-1, 4)
        angles = dihedral_angles(points[conn])
        check(angles.min() >= 30 - 0.05 and angles.max() <= LARGEST + 0.05,
              "%s: %d tets, dihedral angles %.2f to %.2f degrees" % (name, len(conn), angles.min(), angles.max()))
        crowded, hanging = conformity(points, conn)
        check(crowded == 0 and hanging == 0, "%s: no face in 3+ tets (%d), no hanging vertex (%d)" % (name, crowded, hanging))
        for label, tissue in sorted(report["tissues"].items(), key=lambda kv: int(kv[0])):
            check(0 <= tissue["fidelity_f1"] <= 1 and 0 <= tissue["fidelity_f2"] <= 1,
                  "%s tissue %s: F1 %.4f, F2 %.4f" % (name, label, tissue["fidelity_f1"], tissue["fidelity_f2"]))
            check(tissue["components_in_mesh"] == tissue["components"],
                  "%s tissue %s: %d of %d components of 8+ voxels kept" % (name, label, tissue["components_in_mesh"], tissue["components"]))
        reason = report["refinement"]["stop_reason"]
        reached = reason.startswith("every tissue reached the fidelity target") and "below it" not in reason
        if reached:
            check(all(min(t["fidelity_f1"], t["fidelity_f2"]) >= 0.95 for t in report["tissues"].values()),
                  "%s: every tissue at F >= 0.95 as the stop reason says" % name)
        print("     %s: %s after %d passes" % (name, report["refinement"]["stop_reason"], report["refinement"]["passes"]))
check.finish()
