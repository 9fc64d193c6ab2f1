#!/usr/bin/env python3
"""Runs `cbc3d` on every image in ../shared/data with the paper's settings and prints a table:
tets, points, dihedral angles, Hausdorff distance, voxel fidelity, components, seconds per
stage and peak memory. Asserts nothing (timings are noisy): read the figures.

    python3 Testing/Benchmark/benchmark_meshing.py [build/bin/cbc3d] [--iterations N]
"""
import json
import os
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(os.path.dirname(here))
cli = next((a for a in sys.argv[1:] if not a.startswith("--")), os.path.join(root, "build", "bin", "cbc3d"))
iterations = sys.argv[sys.argv.index("--iterations") + 1] if "--iterations" in sys.argv else "0"
shared = os.path.join(root, "..", "shared", "data")
if not os.path.isdir(shared):
    print("skipped: no ../shared/data beside the checkout")
    sys.exit(0)

images = [("cbc3d-brain.nii.gz", []), ("cbc3d-nidus.nii.gz", []), ("cbc3d-ventricles.nii.gz", []),
          ("nipype-tissue-labels.nii.gz", []), ("itk-t1-kmeans-labels.nii.gz", ["--background", "1"])]
print("cbc3d --bcc-size 8 --fidelity 0.95 --pattern edge --iterations %s" % iterations)
print("| image | tets | points | min/max dihedral | HD mm | F1 / F2 (worst tissue) | components kept | lattice s | refinement s | total s | peak MB |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
with tempfile.TemporaryDirectory() as work:
    for name, extra in images:
        out = os.path.join(work, "mesh.vtu")
        report_path = os.path.join(work, "report.json")
        process = subprocess.Popen([cli, os.path.join(shared, name), "-o", out, "--bcc-size", "8", "--fidelity", "0.95",
                                    "--pattern", "edge", "--iterations", iterations, "--quiet", "--report", report_path] + extra,
                                   stderr=subprocess.PIPE, text=True)
        _, status, usage = os.wait4(process.pid, 0)  # this run's own peak memory
        if os.waitstatus_to_exitcode(status) != 0:
            print("| %s | failed: %s |" % (name, process.stderr.read().strip()))
            continue
        r = json.load(open(report_path))
        tissues = r["tissues"].values()
        f1 = min(t.get("fidelity_f1", float("nan")) for t in tissues)
        f2 = min(t.get("fidelity_f2", float("nan")) for t in tissues)
        kept = sum(t.get("components_in_mesh", 0) for t in tissues)
        total = sum(t.get("components", 0) for t in tissues)
        s = r["seconds"]
        print("| %s | %d | %d | %.2f / %.2f | %.2f | %.4f / %.4f | %d / %d | %.2f | %.2f | %.2f | %s |" % (
            name, r["tetrahedra"], r["points"], r["min_dihedral_deg"], r["max_dihedral_deg"], r["hausdorff_mm"] or float("nan"),
            f1, f2, kept, total, s["lattice"], s.get("refinement", 0.0), s["total"],
            "%.0f" % (usage.ru_maxrss / 1024.0)))
