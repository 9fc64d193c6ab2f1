# pvpython, real image: the deformation's target points on cbc3d-nidus.nii.gz, for each
# non-connectivity pattern, are exactly the counts of the CBC3D paper's Table 1 (2770 / 3498 /
# 6213 / 11755 for vertex / edge / face / none). Skips (77) without ../shared/data.
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, shared_data_or_skip  # noqa: E402

shared = shared_data_or_skip()
cli = os.environ["CBC3D_CLI"]
check = Checks()
PAPER_TABLE_1 = {"vertex": 2770, "edge": 3498, "face": 6213, "none": 11755}

with tempfile.TemporaryDirectory() as work:
    for pattern, expected in PAPER_TABLE_1.items():
        report_path = os.path.join(work, pattern + ".json")
        result = subprocess.run([cli, os.path.join(shared, "cbc3d-nidus.nii.gz"), "-o", os.path.join(work, "mesh.vtu"),
                                 "--bcc-size", "8", "--pattern", pattern, "--iterations", "1", "--quiet",
                                 "--report", report_path], capture_output=True, text=True, timeout=600)
        if not check(result.returncode == 0, "nidus, pattern %s: cbc3d exits 0 %s" % (pattern, result.stderr.strip())):
            continue
        targets = json.load(open(report_path))["deformation"]["targets"]
        check(targets == expected, "nidus, pattern %s: %d target points (paper's Table 1: %d)" % (pattern, targets, expected))
check.finish()
