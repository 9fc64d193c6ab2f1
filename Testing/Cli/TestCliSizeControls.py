"""--max-edge [LABEL=]MM, --min-edge MM, --fidelity LABEL=F and --max-tets N do what they say: every edge of
the mesh is measured here, in the Medit file the command writes, against the limits; a run
without the options shows that the limits are what made the difference. With the shared data,
the 3 mm head (nipype) at defaults with --max-edge 3=4 --max-edge 8, deformation included, and
--max-tets on the 3 mm head, the k-means head and the New York Head, and the k-means head's
components at the paper's settings."""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from cbc3d_testing import Checks  # noqa: E402

CLI = os.environ["CBC3D_CLI"]
SOURCE = os.environ["CBC3D_SOURCE_DIR"]
SHARED = os.environ.get("CBC3D_SHARED_DATA", "")
SHELLS = os.path.join(SOURCE, "Data", "nested_shells.vti")  # tissues 1, 2, 3 in 1 mm voxels
EDGES = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))
check = Checks()


def read_medit(path):
    """Points and (tet, label) pairs of a Medit .mesh file."""
    words = " ".join(line for line in open(path) if not line.startswith("#")).split()
    points, tets = [], []
    i = 0
    while i < len(words):
        if words[i] == "Vertices":
            n = int(words[i + 1])
            points = [tuple(float(v) for v in words[i + 2 + 4 * k:i + 5 + 4 * k]) for k in range(n)]
            i += 2 + 4 * n
        elif words[i] == "Tetrahedra":
            n = int(words[i + 1])
            tets = [([int(v) - 1 for v in words[i + 2 + 5 * k:i + 6 + 5 * k]], int(words[i + 6 + 5 * k]))
                    for k in range(n)]
            i += 2 + 5 * n
        else:
            i += 1
    return points, tets


def edge_ranges(path):
    """Per label: (shortest, longest) edge."""
    points, tets = read_medit(path)
    ranges = {}
    for tet, label in tets:
        lengths = [math.dist(points[tet[a]], points[tet[b]]) for a, b in EDGES]
        low, high = ranges.get(label, (math.inf, 0.0))
        ranges[label] = (min(low, min(lengths)), max(high, max(lengths)))
    return ranges


def mesh(image, options, work, name):
    out = os.path.join(work, name + ".mesh")
    report = os.path.join(work, name + ".json")
    result = subprocess.run([CLI, image, "-o", out, "--report", report, "--quiet"] + options,
                            capture_output=True, text=True, timeout=1200)
    if not check(result.returncode == 0, "%s: cbc3d %s ran (%s)" % (name, " ".join(options), result.stderr.strip())):
        return {}, {}
    return edge_ranges(out), json.load(open(report))


def phantom_cases(work):
    lattice_only = ["--bcc-size", "8", "--fidelity", "0", "--iterations", "0"]
    plain, _ = mesh(SHELLS, lattice_only, work, "plain")
    check(all(high > 4.0 for _, high in plain.values()), "without limits every tissue has edges over 4 mm: %s" % plain)
    limited, report = mesh(SHELLS, lattice_only + ["--max-edge", "3=2", "--max-edge", "4"], work, "limited")
    check(sorted(limited) == [1, 2, 3], "the limited mesh has tissues 1, 2, 3: %s" % sorted(limited))
    check(limited.get(3, (0, 99))[1] <= 2.0 + 1e-6, "tissue 3: every edge at most 2 mm: %s" % (limited.get(3),))
    for label in (1, 2):
        check(limited.get(label, (0, 99))[1] <= 4.0 + 1e-6,
              "tissue %d: every edge at most 4 mm: %s" % (label, limited.get(label)))
    check(report.get("parameters", {}).get("tissue_max_edge_mm") == {"3": 2.0},
          "the report names the per-tissue limit: %s" % report.get("parameters", {}).get("tissue_max_edge_mm"))
    check(report.get("refinement", {}).get("overlong_tets") == 0, "the report counts no overlong tet")

    # The floor: refinement for fidelity stops at 3 mm edges (the default floor is the voxel, 1 mm).
    fine, _ = mesh(SHELLS, ["--bcc-size", "8", "--iterations", "0"], work, "fine")
    check(min(low for low, _ in fine.values()) < 3.0, "without a floor some edge is under 3 mm: %s" % fine)
    floored, _ = mesh(SHELLS, ["--bcc-size", "8", "--iterations", "0", "--min-edge", "3"], work, "floored")
    check(floored and min(low for low, _ in floored.values()) >= 3.0 - 1e-6,
          "with --min-edge 3 no edge is under 3 mm: %s" % floored)

    # Fidelity per tissue: tissue 3 alone refined, the others at the lattice.
    _, per_tissue = mesh(SHELLS, ["--bcc-size", "8", "--iterations", "0", "--fidelity", "0",
                                  "--fidelity", "3=0.9"], work, "per_tissue")
    tissues = per_tissue.get("tissues", {})
    f3 = tissues.get("3", {})
    check(min(f3.get("fidelity_f1", 0), f3.get("fidelity_f2", 0)) >= 0.9 or
          "minimum edge" in per_tissue.get("refinement", {}).get("stop_reason", ""),
          "tissue 3 reaches its own fidelity 0.9 or the floor: %s" % f3)


def shared_cases(work):
    if os.path.isdir(SHARED):
        head = os.path.join(SHARED, "nipype-tissue-labels.nii.gz")
        sized, _ = mesh(head, ["--max-edge", "3=4", "--max-edge", "8"], work, "nipype")
        check(sized.get(3, (0, 99))[1] <= 4.0 + 1e-6, "nipype tissue 3: every edge at most 4 mm: %s" % (sized.get(3),))
        for label in (1, 2):
            check(sized.get(label, (0, 99))[1] <= 8.0 + 1e-6,
                  "nipype tissue %d: every edge at most 8 mm: %s" % (label, sized.get(label)))
        # Tet budgets: within [0.9 N, N], every tissue within 3% of its voxels' volume, angles
        # in [20, 160] degrees, and the report says the budget stopped refinement.
        for image, budget, extra in (("nipype-tissue-labels.nii.gz", 20000, []),
                                     ("nipype-tissue-labels.nii.gz", 50000, []),
                                     ("nipype-tissue-labels.nii.gz", 100000, []),
                                     ("itk-t1-kmeans-labels.nii.gz", 100000, ["--background", "1"]),
                                     ("nyhead-6tissue-1mm.nii.gz", 300000, [])):
            name = "%s at %d" % (image.split("-")[0], budget)
            _, r = mesh(os.path.join(SHARED, image), ["--max-tets", str(budget)] + extra, work, "budget")
            tets = r.get("tetrahedra", 0)
            check(0.9 * budget <= tets <= budget, "%s: %d tets, within [0.9 N, N]" % (name, tets))
            check(r.get("refinement", {}).get("stop_reason") == "the tet budget is spent",
                  "%s: the report says the budget stopped refinement" % name)
            check(r.get("topology", {}).get("solver_ready") is True, "%s: ready for a solver" % name)
            check(20.0 - 1e-6 <= r.get("min_dihedral_deg", 0) and r.get("max_dihedral_deg", 180) <= 160.0 + 1e-6,
                  "%s: angles in [20, 160]: %s, %s" % (name, r.get("min_dihedral_deg"), r.get("max_dihedral_deg")))
            volumes = {label: t["volume_mm3"] / t["image_volume_mm3"] for label, t in r.get("tissues", {}).items()}
            check(volumes and all(abs(v - 1.0) <= 0.03 for v in volumes.values()),
                  "%s: every tissue within 3%% of its voxels' volume: %s" % (name, volumes))
        # A coarse model of a fine image: --min-edge 4 on the 1 mm New York Head, before deformation.
        coarse, _ = mesh(os.path.join(SHARED, "nyhead-6tissue-1mm.nii.gz"), ["--min-edge", "4", "--iterations", "0"],
                         work, "coarse")
        check(coarse and min(low for low, _ in coarse.values()) >= 4.0 - 1e-6,
              "New York Head, --min-edge 4: no edge under 4 mm before deformation: %s" % coarse)
        # Components: at the paper's settings the k-means head keeps tets of its tissue in every
        # component of 8 voxels or more (the refinement's count), before deformation, and is sound.
        _, r = mesh(os.path.join(SHARED, "itk-t1-kmeans-labels.nii.gz"),
                    ["--bcc-size", "8", "--fidelity", "0.95", "--pattern", "edge", "--iterations", "0",
                     "--background", "1"], work, "components")
        kept = {label: (t.get("components_in_mesh"), t.get("components")) for label, t in r.get("tissues", {}).items()}
        check(kept and all(k == n for k, n in kept.values()) and sum(n for _, n in kept.values()) > 200,
              "k-means head, paper settings: every component of 8 voxels or more kept: %s" % kept)
        check(r.get("topology", {}).get("solver_ready") is True, "k-means head, paper settings: ready for a solver")
    else:
        print("SKIP: the nipype, k-means and New York Head cases need ../shared/data")
        sys.exit(77)


# `shared`: the cases on the real images (ctest label data), else those on the bundled phantom.
with tempfile.TemporaryDirectory() as work:
    if sys.argv[1:] == ["shared"]:
        shared_cases(work)
    else:
        phantom_cases(work)
check.finish()
