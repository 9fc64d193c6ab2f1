#!/usr/bin/env python3
"""Meshes every image in ../shared/data with the paper's settings (Table 3: `--bcc-size 8
--fidelity 0.95 --pattern edge --iterations 5`; background 1 for the k-means head) and prints
a Markdown table: tets, points, dihedral angles, Hausdorff distance, voxel fidelity, components,
seconds per stage and peak memory. Where the CGAL Mesh_3 peer was built (Debian's libcgal-dev
installed before configuring), it meshes the same images with the paper's CGAL settings, time
limits off (deterministic), measured by the same quality filter, and the table puts both side by
side with ratios. Writes the figures as JSON too. Asserts nothing: read the figures.

    python3 Testing/Benchmark/benchmark_meshing.py [BUILD_DIR] [--iterations N] [--json FILE] [--no-cgal]
"""
import json
import os
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(os.path.dirname(here))
args = sys.argv[1:]


def option(name, default):
    return args[args.index(name) + 1] if name in args else default


positional = [a for i, a in enumerate(args) if not a.startswith("--") and (i == 0 or not args[i - 1] in ("--iterations", "--json"))]
build = positional[0] if positional else os.path.join(root, "build")
if os.path.basename(build) == "cbc3d":  # a path to the binary also works
    build = os.path.dirname(os.path.dirname(build))
cli = os.path.join(build, "bin", "cbc3d")
cgal = os.path.join(build, "bin", "CBC3DCGALMesh3")
iterations = option("--iterations", "5")
json_path = option("--json", "benchmark.json")
use_cgal = "--no-cgal" not in args and os.path.exists(cgal)
shared = os.path.join(root, "..", "shared", "data")
if not os.path.isdir(shared):
    print("skipped: no ../shared/data beside the checkout")
    sys.exit(0)

# The paper's Table 4, case 1 (= cbc3d-brain.nii.gz).
PAPER = {"cbc3d-brain.nii.gz": {"CBC3D paper": (69101, 12.20, 157.67, 3.47), "CGAL 4.5.2 (paper)": (414470, 12.01, 162.27, 3.21)}}


images = [("cbc3d-brain.nii.gz", 0), ("cbc3d-nidus.nii.gz", 0), ("cbc3d-ventricles.nii.gz", 0),
          ("nipype-tissue-labels.nii.gz", 0), ("itk-t1-kmeans-labels.nii.gz", 1)]
results = {}
print("cbc3d --bcc-size 8 --fidelity 0.95 --pattern edge --iterations %s%s" % (
    iterations, "; CGAL Mesh_3: facet angle 30, size 2, distance 2, radius-edge 1.5, cell size 2.5, no time limits" if use_cgal else "; CGAL peer not built"))
print()
print("| image | mesher | tets | points | min / max dihedral | HD mm (95%, mean) | F1 / F2 worst | seconds | peak MB |")
print("|---|---|---|---|---|---|---|---|---|")
with tempfile.TemporaryDirectory() as work:
    for name, background in images:
        path = os.path.join(shared, name)
        report_path = os.path.join(work, "report.json")
        process = subprocess.Popen([cli, path, "-o", os.path.join(work, "mesh.vtu"), "--bcc-size", "8", "--fidelity", "0.95",
                                    "--pattern", "edge", "--iterations", iterations, "--background", str(background),
                                    "--quiet", "--report", report_path], stderr=subprocess.PIPE, text=True)
        _, status, usage = os.wait4(process.pid, 0)  # this run's own peak memory
        entry = results.setdefault(name, {})
        if os.waitstatus_to_exitcode(status) != 0:
            print("| %s | cbc3d | failed: %s |" % (name, process.stderr.read().strip()))
            continue
        r = json.load(open(report_path))
        tissues = r["tissues"].values()
        entry["cbc3d"] = dict(r, peak_mb=usage.ru_maxrss / 1024.0)
        print("| %s | cbc3d | %d | %d | %.2f / %.2f | %.2f (%.2f, %.2f) | %.3f / %.3f | %.2f | %.0f |" % (
            name, r["tetrahedra"], r["points"], r["min_dihedral_deg"], r["max_dihedral_deg"], r["hausdorff_mm"],
            r["hausdorff_95_mm"], r["mean_distance_mm"], min(t.get("fidelity_f1", float("nan")) for t in tissues),
            min(t.get("fidelity_f2", float("nan")) for t in tissues), r["seconds"]["total"], usage.ru_maxrss / 1024.0))
        if use_cgal:
            process = subprocess.Popen([cgal, path, os.path.join(work, "cgal.vtu"), "--background", str(background), "--deterministic"],
                                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            out = process.stdout.read()
            _, status, usage = os.wait4(process.pid, 0)
            lines = [l for l in out.splitlines() if l.startswith("{")]
            if os.waitstatus_to_exitcode(status) != 0 or not lines:
                print("| %s | CGAL Mesh_3 | failed |" % name)
            else:
                c = dict(json.loads(lines[-1]), peak_mb=usage.ru_maxrss / 1024.0)
                entry["cgal"] = c
                print("| %s | CGAL Mesh_3 | %d | %d | %.2f / %.2f | %.2f (%.2f, %.2f) | | %.2f | %.0f |" % (
                    name, c["tetrahedra"], c["points"], c["min_dihedral_deg"], c["max_dihedral_deg"], c["hausdorff_mm"],
                    c["hausdorff_95_mm"], c["mean_distance_mm"], c["seconds"], c["peak_mb"]))
                o = entry["cbc3d"]
                print("| %s | ratio cbc3d / CGAL | %.2f | | | %.2f | | %.3f | |" % (
                    name, o["tetrahedra"] / c["tetrahedra"], o["hausdorff_mm"] / c["hausdorff_mm"], o["seconds"]["total"] / c["seconds"]))
        for label, (tets, lo, hi, hd) in PAPER.get(name, {}).items():
            print("| %s | %s | %d | | %.2f / %.2f | %.2f | | | |" % (name, label, tets, lo, hi, hd))
with open(json_path, "w") as out:
    json.dump(results, out, indent=2)
print()
print("figures written to %s" % json_path)
