"""The rule for changes that alter meshes: two builds of cbc3d mesh every shared image at the
paper's settings and at defaults, and each figure of the second (after) is judged against the
first's (before).

    python3 Testing/Benchmark/judge_change.py BEFORE_CLI AFTER_CLI [--heads] [--images NAME ...]

A change passes when on every case the mesh stays ready for a solver; its angles stay in
[20, 160] degrees; its tets change by at most 2%; every tissue's volume changes by at most 0.5%;
its 95th-percentile and mean Hausdorff distances grow by at most 2%; and its maximum grows by
at most half the largest voxel spacing, on tissues of 1,000 voxels or more. Prints a line a
case and tissue with both figures, then the verdict; exits 1 when a figure fails. --heads adds
the 1 mm New York Head (a minute or more a run).
"""
import argparse
import json
import os
import struct
import subprocess
import sys
import tempfile

import benchmark_meshing as meshing

# The paper's settings (the iterations are the default 5) and the shared images with the label
# that is not tissue, as the benchmark meshes them.
PAPER = meshing.PAPER_SETTINGS
IMAGES = meshing.IMAGES
HEADS = meshing.CURVE_HEADS


def voxel_spacing(path):
    """The NIfTI header's pixdim[1..3]."""
    with meshing.open_nifti(path) as stream:
        header, order = meshing.read_nifti_header(stream)
    return struct.unpack_from(order + "3f", header, 80)


def report(cli, image, options, work):
    """The run's JSON report."""
    path = os.path.join(work, "report.json")
    command = [cli, image, "-o", os.path.join(work, "mesh.vtu"), "--report", path, "--quiet"] + options
    subprocess.run(command, check=True)
    with open(path) as f:
        return json.load(f)


def judge_case(name, before, after, spacing, failures):
    """Prints the case's figures and appends each failed one to `failures`."""
    def check(ok, text):
        print("  %-6s %s" % ("ok" if ok else "FAIL", text))
        if not ok:
            failures.append("%s: %s" % (name, text))

    print(name)
    check(after["topology"]["solver_ready"], "ready for a solver")
    check(after["min_dihedral_deg"] >= 20.0 and after["max_dihedral_deg"] <= 160.0,
          "angles %.2f-%.2f (before %.2f-%.2f)" % (after["min_dihedral_deg"], after["max_dihedral_deg"],
                                                   before["min_dihedral_deg"], before["max_dihedral_deg"]))
    tets, was = after["tetrahedra"], before["tetrahedra"]
    check(abs(tets - was) <= 0.02 * was, "tets %d (before %d, %+.2f%%)" % (tets, was, 100.0 * (tets - was) / was))
    half_voxel = 0.5 * max(spacing)
    voxel = spacing[0] * spacing[1] * spacing[2]
    for tissue, b in sorted(before["tissues"].items(), key=lambda item: int(item[0])):
        a = after["tissues"].get(tissue)
        if a is None:
            check(False, "tissue %s meshed" % tissue)
            continue
        volume = (a["volume_mm3"] - b["volume_mm3"]) / b["volume_mm3"]
        check(abs(volume) <= 0.005, "tissue %s: volume %+.3f%%" % (tissue, 100.0 * volume))
        check(a["hausdorff_95_mm"] <= 1.02 * b["hausdorff_95_mm"] + 1e-9 and
              a["mean_distance_mm"] <= 1.02 * b["mean_distance_mm"] + 1e-9,
              "tissue %s: Hausdorff 95%% %.3f (before %.3f), mean %.3f (%.3f) mm" % (
                  tissue, a["hausdorff_95_mm"], b["hausdorff_95_mm"], a["mean_distance_mm"], b["mean_distance_mm"]))
        judged = b["image_volume_mm3"] / voxel >= 1000
        check(not judged or a["hausdorff_mm"] <= b["hausdorff_mm"] + half_voxel,
              "tissue %s: Hausdorff maximum %.3f (before %.3f) mm%s" % (
                  tissue, a["hausdorff_mm"], b["hausdorff_mm"], "" if judged else ", under 1,000 voxels: not judged"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--heads", action="store_true", help="also the 1 mm New York Head")
    parser.add_argument("--images", nargs="+", metavar="NAME", help="only images whose name holds one of these")
    options = parser.parse_args()
    if not os.path.isdir(meshing.SHARED):
        print("judge_change: %s is absent: nothing to judge" % os.path.normpath(meshing.SHARED))
        return 0
    images = IMAGES + (HEADS if options.heads else [])
    if options.images:
        images = [(n, b) for n, b in images if any(part in n for part in options.images)]
    failures = []
    with tempfile.TemporaryDirectory() as work:
        for image, background in images:
            path = os.path.join(meshing.SHARED, image)
            spacing = voxel_spacing(path)
            for setting, extra in (("paper", PAPER), ("defaults", [])):
                run = extra + ["--background", str(background)]
                before = report(options.before, path, run, work)
                after = report(options.after, path, run, work)
                judge_case("%s, %s" % (image, setting), before, after, spacing, failures)
    print("\n%d figures fail the rule" % len(failures) if failures else "\nevery figure meets the rule")
    for failure in failures:
        print("  " + failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
