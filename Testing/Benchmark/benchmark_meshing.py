#!/usr/bin/env python3
"""Benchmark of cbc3d on the real images of ../shared/data, with CGAL Mesh_3 beside it.

Meshes every image with the paper's settings (Table 3: `--bcc-size 8 --fidelity 0.95 --pattern
edge --iterations 5`; background 1 for the k-means head) and prints Markdown tables:

- comparison: tets, points, dihedral angles, Hausdorff distance (HD), voxel fidelity, seconds and
  peak memory of cbc3d; where the CGAL Mesh_3 peer was built (Debian's libcgal-dev installed
  before configuring), CGAL on the same image with the paper's CGAL settings, once with the
  perturber's and exuder's time limits off (deterministic) and once or more (--cgal-runs) by
  default, where those limits make the result depend on the machine's load; the ratios are
  cbc3d against the deterministic run; the paper's published figures where it has them;
- cbc3d's seconds per stage;
- HD per tissue, cbc3d and CGAL;
- topology per tissue and of the whole mesh, cbc3d and CGAL: components through faces and
  through vertices, hinged parts, non-manifold surface edges and vertices, the surface's Euler
  characteristic against the image's, and whether the mesh is ready for a solver;
- scaling: the brain upsampled 2x and 4x per axis (nearest neighbour, same world extent), meshed
  by cbc3d at 1 and 2 threads (and all cores where there are more): time and memory against
  image size and thread count.

--curves replaces all of these by size curves: on each image, cbc3d at several tet budgets
(--max-tets; size_curves.py) and CGAL at several multiples of the paper's size criteria, each mesh's tets, Hausdorff distance
(max and 95th percentile) and seconds, printed as a table, written as JSON and drawn with
matplotlib (one PNG per image: HD against tets and seconds against tets). Only that mode imports
matplotlib; without it the plots are skipped with a message. Then each cbc3d mesh against CGAL
at the same tets, interpolated along CGAL's curve (--images nyhead adds the 1 mm New York Head).

Writes every figure as JSON too. Asserts nothing: read the figures. Exits 0 with a message
where ../shared/data is missing.

    python3 Testing/Benchmark/benchmark_meshing.py [BUILD_DIR] [--iterations N] [--json FILE]
        [--no-cgal] [--cgal-runs N] [--images NAME ...] [--no-scaling | --scaling-only]
        [--scaling-factors 1,2,4] [--scaling-threads 1,2] [--no-targets]
    /usr/bin/python3 Testing/Benchmark/benchmark_meshing.py [BUILD_DIR] --curves [--curve-budgets 20000,50000,...]
        [--curve-cgal-factors 0.35,0.5,0.75,1,1.5,2,3,4] [--curve-cgal-limit SECONDS] [--no-curve-cgal-default]
        [--plots DIR] [--images NAME ...] [--no-cgal] [--json FILE]
    /usr/bin/python3 Testing/Benchmark/benchmark_meshing.py --curves-from JSON [--plots DIR] [--images NAME ...]
"""
import argparse
import array
import gzip
import json
import math
import os
import resource
import struct
import subprocess
import sys
import tempfile
import time

import size_curves
import speed_targets

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SHARED = os.path.join(ROOT, "..", "shared", "data")
PAPER_SETTINGS = ["--bcc-size", "8", "--fidelity", "0.95", "--pattern", "edge"]
CGAL_SETTINGS = "facet angle 30, size 2, distance 2, radius-edge 1.5, cell size 2.5"
# The paper's CGAL size criteria in mm, which --curves scales: facet size, facet distance, cell size.
CGAL_SIZES = (2.0, 2.0, 2.5)
STAGES = ("read", "lattice", "refinement", "deformation", "quality", "write")
IMAGES = [("cbc3d-brain.nii.gz", 0), ("cbc3d-nidus.nii.gz", 0), ("cbc3d-ventricles.nii.gz", 0),
          ("nipype-tissue-labels.nii.gz", 0), ("itk-t1-kmeans-labels.nii.gz", 1)]
# The size curves also run on a real 1 mm head (--images nyhead; --curve-budgets up to 3000000).
CURVE_HEADS = [("nyhead-6tissue-1mm.nii.gz", 0)]
SCALING_IMAGE = "cbc3d-brain.nii.gz"
# The paper's Table 4, case 1 (= cbc3d-brain.nii.gz): tets, min and max dihedral, HD.
PAPER = {"cbc3d-brain.nii.gz": {"CBC3D paper": (69101, 12.20, 157.67, 3.47),
                                "CGAL 4.5.2 (paper)": (414470, 12.01, 162.27, 3.21)}}


def parse_arguments():
    parser = argparse.ArgumentParser(description="cbc3d benchmark on ../shared/data, CGAL Mesh_3 beside it")
    parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"),
                        help="build folder, or the path of its bin/cbc3d (default: build)")
    parser.add_argument("--iterations", default="5", help="cbc3d deformation iterations (default 5, the paper's)")
    parser.add_argument("--json", help="where the figures go (default benchmark.json; benchmark-curves.json "
                        "with --curves)")
    parser.add_argument("--no-cgal", action="store_true", help="cbc3d alone")
    parser.add_argument("--cgal-runs", type=int, default=1,
                        help="CGAL default (time-limited) runs per image, to show their spread (default 1)")
    parser.add_argument("--images", nargs="+", metavar="NAME",
                        help="only the images whose file name contains one of these")
    parts = parser.add_mutually_exclusive_group()
    parts.add_argument("--no-scaling", action="store_true", help="skip the scaling runs")
    parts.add_argument("--scaling-only", action="store_true", help="only the scaling runs")
    parser.add_argument("--scaling-factors", default="1,2,4", help="upsampling factors per axis (default 1,2,4)")
    parser.add_argument("--scaling-threads", help="thread counts (default 1,2 and all cores where there are more)")
    parser.add_argument("--no-targets", action="store_true",
                        help="skip the speed targets' runs (threads, padding, a coarse lattice)")
    add_curve_arguments(parser, parts)
    options = parser.parse_args()
    if os.path.basename(options.build) == "cbc3d":  # a path to the binary also works
        options.build = os.path.dirname(os.path.dirname(options.build))
    options.factors = [int(f) for f in options.scaling_factors.split(",")]
    options.curve_budgets = [int(b) for b in positive_numbers(parser, "--curve-budgets", options.curve_budgets)]
    options.curve_cgal_factors = positive_numbers(parser, "--curve-cgal-factors", options.curve_cgal_factors)
    if options.json is None:
        options.json = "benchmark-curves.json" if options.curves else "benchmark.json"
    options.threads = ([int(t) for t in options.scaling_threads.split(",")] if options.scaling_threads
                       else sorted({1, 2, os.cpu_count() or 1}))
    return options


def add_curve_arguments(parser, parts):
    """The --curves mode's options; --curves is one more choice beside --no-scaling and --scaling-only."""
    parts.add_argument("--curves", action="store_true",
                       help="size curves (HD and seconds against tets) instead of the tables")
    parser.add_argument("--curve-budgets", default="20000,50000,100000,200000,500000,1000000",
                        help="cbc3d tet budgets, --max-tets (default 20000,50000,100000,200000,500000,1000000)")
    parser.add_argument("--curve-cgal-factors", default="0.35,0.5,0.75,1,1.5,2,3,4",
                        help="multiples of the paper's CGAL facet size, facet distance and cell size "
                        "(2, 2, 2.5 mm; default 0.35,0.5,0.75,1,1.5,2,3,4)")
    parser.add_argument("--curve-cgal-limit", type=float, default=300.0, metavar="SECONDS",
                        help="skip a CGAL factor whose predicted no-time-limit run (the previous, coarser one's "
                        "seconds times the cube of the size ratio) exceeds this (default 300; 0: no limit)")
    parser.add_argument("--no-curve-cgal-default", action="store_true",
                        help="skip CGAL's default (time-limited) run at each factor")
    parser.add_argument("--plots", default=os.path.join(ROOT, "Documentation", "images"),
                        help="folder of the PNGs (default Documentation/images)")
    parser.add_argument("--curves-from", metavar="JSON",
                        help="run nothing: print the table and draw the plots of an earlier --curves run's "
                        "JSON (its images, or those of --images)")


def positive_numbers(parser, name, text):
    """A comma-separated list of numbers above 0, or the parser's one-line error."""
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if not values or any(not v > 0 or v == float("inf") for v in values):
        parser.error("%s %s: expected numbers above 0, separated by commas" % (name, text))
    return values


def progress(text):
    """Progress goes to stderr so that stdout holds only the tables."""
    print(text, file=sys.stderr, flush=True)


def available_memory_bytes():
    with open("/proc/meminfo") as meminfo:
        for line in meminfo:
            if line.startswith("MemAvailable:"):
                return int(line.split()[1]) * 1024
    return None


def run_measured(command, memory_limit=None):
    """Runs command; returns its exit code, stdout, stderr, wall seconds and its own peak resident
    memory in MB. memory_limit caps its address space, so that a run too big for the machine
    fails by itself instead of calling the kernel's OOM killer onto other processes."""
    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (memory_limit, memory_limit))
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        start = time.monotonic()
        process = subprocess.Popen(command, stdout=out, stderr=err, text=True,
                                   preexec_fn=limit if memory_limit else None)
        _, status, usage = os.wait4(process.pid, 0)  # this child's own rusage, not the script's
        process.returncode = os.waitstatus_to_exitcode(status)
        seconds = time.monotonic() - start
        out.seek(0)
        err.seek(0)
        return process.returncode, out.read(), err.read(), seconds, usage.ru_maxrss / 1024.0


def failure(code, err):
    """A short reason for a failed run, for the table: how it ended and its last message."""
    lines = err.strip().splitlines()
    ending = "killed by signal %d" % -code if code < 0 else "exit %d" % code
    return ending + (": " + lines[-1].strip() if lines else "")


def run_cbc3d(cli, image, background, iterations, work, threads=0, memory_limit=None, extra=(),
              settings=PAPER_SETTINGS):
    """cbc3d with the paper's settings (or settings): its --report figures plus peak_mb and
    wall_seconds, or {"error": reason}."""
    report = os.path.join(work, "report.json")
    if os.path.exists(report):
        os.remove(report)
    command = [cli, image, "-o", os.path.join(work, "mesh.vtu")] + list(settings) + [
        "--iterations", iterations, "--background", str(background), "--threads", str(threads),
        "--quiet", "--report", report] + list(extra)
    code, _, err, seconds, peak = run_measured(command, memory_limit)
    if code != 0:
        return {"error": failure(code, err), "peak_mb": peak}
    with open(report) as r:
        return dict(json.load(r), peak_mb=peak, wall_seconds=seconds)


def run_cgal(cgal, image, background, work, deterministic, sizes=()):
    """The CGAL Mesh_3 peer (the paper's criteria, or sizes: its size options): its JSON line
    (seconds = make_mesh_3 alone) plus peak_mb and wall_seconds (reading, meshing, measuring,
    writing), or {"error": reason}."""
    command = [cgal, image, os.path.join(work, "cgal.vtu"), "--background", str(background)] + list(sizes)
    code, out, err, seconds, peak = run_measured(command + (["--deterministic"] if deterministic else []))
    lines = [line for line in out.splitlines() if line.startswith("{")]
    if code != 0 or not lines:
        return {"error": failure(code, err), "peak_mb": peak}
    return dict(json.loads(lines[-1]), peak_mb=peak, wall_seconds=seconds)


def print_table(header, rows):
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for row in rows:
        print("| " + " | ".join(row) + " |")
    print()


def hd_text(r):
    return "%.2f (%.2f, %.2f)" % (r["hausdorff_mm"], r["hausdorff_95_mm"], r["mean_distance_mm"])


def mesh_row(name, mesher, r, seconds, fidelity=""):
    """One comparison row: a failed run says why in the tets column."""
    if "error" in r:
        return [name, mesher, "failed: " + r["error"]] + [""] * 6
    return [name, mesher, "%d" % r["tetrahedra"], "%d" % r["points"],
            "%.2f / %.2f" % (r["min_dihedral_deg"], r["max_dihedral_deg"]), hd_text(r), fidelity,
            "%.2f" % seconds, "%.0f" % r["peak_mb"]]


def worst_fidelity(r):
    tissues = r["tissues"].values()
    return "%.3f / %.3f" % (min(t.get("fidelity_f1", float("nan")) for t in tissues),
                            min(t.get("fidelity_f2", float("nan")) for t in tissues))


def mesh_images(options, images, cli, cgal):
    """cbc3d, CGAL deterministic and CGAL default on each image: {name: figures}."""
    results = {}
    with tempfile.TemporaryDirectory() as work:
        for name, background in images:
            path = os.path.join(SHARED, name)
            progress("cbc3d on %s" % name)
            entry = results[name] = {"cbc3d": run_cbc3d(cli, path, background, options.iterations, work)}
            if cgal:
                progress("CGAL Mesh_3 (no time limits) on %s" % name)
                entry["cgal_deterministic"] = run_cgal(cgal, path, background, work, True)
                entry["cgal_default"] = []
                for run in range(options.cgal_runs):
                    progress("CGAL Mesh_3 (default) on %s, run %d of %d" % (name, run + 1, options.cgal_runs))
                    entry["cgal_default"].append(run_cgal(cgal, path, background, work, False))
    return results


def print_comparison(results, cgal_runs):
    rows = []
    with_cgal = any("cgal_deterministic" in entry for entry in results.values())
    for name, entry in results.items():
        ours = entry["cbc3d"]
        rows.append(mesh_row(name, "cbc3d", ours, ours.get("seconds", {}).get("total", 0),
                             "" if "error" in ours else worst_fidelity(ours)))
        if "cgal_deterministic" in entry:
            exact = entry["cgal_deterministic"]
            rows.append(mesh_row(name, "CGAL Mesh_3 no time limits", exact, exact.get("seconds", 0)))
            for run, c in enumerate(entry["cgal_default"]):
                label = "CGAL Mesh_3 default" + (" #%d" % (run + 1) if cgal_runs > 1 else "")
                rows.append(mesh_row(name, label, c, c.get("seconds", 0)))
            if "error" not in ours and "error" not in exact:
                rows.append([name, "ratio cbc3d / CGAL no time limits",
                             "%.2f" % (ours["tetrahedra"] / exact["tetrahedra"]), "", "",
                             "%.2f" % (ours["hausdorff_mm"] / exact["hausdorff_mm"]), "",
                             "%.3f" % (ours["seconds"]["total"] / exact["seconds"]), ""])
        for label, (tets, low, high, hd) in PAPER.get(name, {}).items():
            rows.append([name, label, "%d" % tets, "", "%.2f / %.2f" % (low, high), "%.2f" % hd, "", "", ""])
    print("Seconds: cbc3d's whole run (reading, meshing, measuring, writing)%s." % (
        "; CGAL's make_mesh_3 alone. Ratios: cbc3d against CGAL with no time limits (deterministic); "
        "CGAL's default runs stop its perturber and exuder after the time its refinement took, so they "
        "vary with the machine's load" if with_cgal else ""))
    print()
    print_table(["image", "mesher", "tets", "points", "min / max dihedral", "HD mm (95%, mean)",
                 "F1 / F2 worst", "seconds", "peak MB"], rows)


def stage_cells(r):
    return ["%.2f" % r["seconds"][stage] for stage in STAGES + ("total",)]


def print_stages(results):
    rows = [[name] + stage_cells(entry["cbc3d"]) + ["%.0f" % entry["cbc3d"]["peak_mb"]]
            for name, entry in results.items() if "error" not in entry["cbc3d"]]
    print("cbc3d seconds per stage (all cores):")
    print()
    print_table(["image"] + list(STAGES) + ["total", "peak MB"], rows)


def volume_text(t):
    """The tissue's mesh volume as a share of its voxels' volume."""
    return "%.1f%%" % (100.0 * t["volume_mm3"] / t["image_volume_mm3"]) if t and "volume_mm3" in t else "-"


def print_tissues(results):
    """HD and volume per tissue: cbc3d, CGAL deterministic, CGAL default (each run)."""
    rows = []
    for name, entry in results.items():
        ours = entry["cbc3d"]
        if "error" in ours:
            continue
        for label, t in ours["tissues"].items():
            row = [name, label, "%d" % t["tetrahedra"], hd_text(t), volume_text(t),
                   "%.3f / %.3f" % (t.get("fidelity_f1", float("nan")), t.get("fidelity_f2", float("nan")))]
            if "cgal_deterministic" in entry:
                exact = entry["cgal_deterministic"].get("tissues", {}).get(label)
                defaults = [c.get("tissues", {}).get(label) for c in entry["cgal_default"]]
                row += ["%d" % exact["tetrahedra"] if exact else "-", hd_text(exact) if exact else "-",
                        volume_text(exact), ", ".join("%.2f" % c["hausdorff_mm"] if c else "-" for c in defaults)]
            rows.append(row)
    header = ["image", "tissue", "cbc3d tets", "cbc3d HD mm (95%, mean)", "cbc3d volume / image", "cbc3d F1 / F2"]
    if any("cgal_deterministic" in entry for entry in results.values()):
        header += ["CGAL tets", "CGAL no time limits HD mm (95%, mean)", "CGAL volume / image", "CGAL default HD mm"]
    print("Hausdorff distance and volume (mesh / voxels) per tissue (a tissue CGAL lost is '-'):")
    print()
    print_table(header, rows)


def image_euler_text(t):
    """The image's Euler characteristic, and where its voxels pinch, what a manifold surface
    round them has with every pinch joined and parted (cbc3d's report has both)."""
    image = t.get("image_surface_euler")
    if image is None:
        return "-"
    joined, parted = t.get("image_surface_euler_pinches_joined"), t.get("image_surface_euler_pinches_parted")
    if joined is None or parted is None or joined == parted == image:
        return "%d" % image
    return "%d (manifold %d to %d)" % (image, joined, parted)


def topology_cells(t):
    """Face / vertex components, hinged parts, non-manifold edges / vertices, Euler mesh / image."""
    if not t or "face_components" not in t:
        return ["-"] * 4
    return ["%d / %d" % (t["face_components"], t["vertex_components"]), "%d" % t["hinged_parts"],
            "%d / %d" % (t["nonmanifold_edges"], t["nonmanifold_vertices"]),
            "%d / %s" % (t["surface_euler"], image_euler_text(t))]


def print_topology(results):
    """Topology per tissue and of the whole mesh ("all", with the solver verdict): cbc3d and
    CGAL with no time limits side by side."""
    rows = []
    with_cgal = any("cgal_deterministic" in entry for entry in results.values())
    for name, entry in results.items():
        ours = entry["cbc3d"]
        if "error" in ours:
            continue
        exact = entry.get("cgal_deterministic", {})
        theirs = {} if "error" in exact else exact
        for label, t in list(ours["tissues"].items()) + [("all", ours.get("topology"))]:
            other = theirs.get("topology") if label == "all" else theirs.get("tissues", {}).get(label)
            row = [name, label] + topology_cells(t)
            if with_cgal:
                row += topology_cells(other)
            if label == "all":
                ready = lambda r: "-" if not r or "solver_ready" not in r else ("yes" if r["solver_ready"] else "no")
                row[1] = "all (solver ready: cbc3d %s%s)" % (ready(t), ", CGAL " + ready(other) if with_cgal else "")
            rows.append(row)
    columns = ["face / vertex components", "hinged parts", "non-manifold edges / vertices", "Euler mesh / image"]
    header = ["image", "tissue"] + ["cbc3d " + c for c in columns]
    if with_cgal:
        header += ["CGAL " + c for c in columns]
    print("Topology per tissue (its surface: faces with one tet of it) and of the whole mesh (its boundary; "
          "its non-manifold counts include every tissue's)%s:" % ("; CGAL with no time limits" if with_cgal else ""))
    print()
    print_table(header, rows)


def read_nifti_header(stream):
    """The bytes up to the voxels (header and extensions) and the byte order."""
    start = stream.read(352)
    order = "<" if struct.unpack("<i", start[:4])[0] == 348 else ">"
    if struct.unpack(order + "i", start[:4])[0] != 348:
        raise ValueError("not a NIfTI-1 file")
    offset = int(struct.unpack(order + "f", start[108:112])[0])
    return bytearray(start + stream.read(max(0, offset - 352))), order


def open_nifti(path):
    return gzip.open(path, "rb") if path.endswith(".gz") else open(path, "rb")


def voxel_count(path):
    with open_nifti(path) as stream:
        header, order = read_nifti_header(stream)
    nx, ny, nz = struct.unpack_from(order + "3h", header, 42)
    return nx * ny * nz


def upsampled_header(header, order, factor):
    """The header of the image upsampled factor times per axis over the same world extent: sizes
    times factor, spacing and both frames' axes divided by it, and origins moved to the first
    new voxel's centre, (factor - 1) / (2 factor) of an old voxel before the old one's."""
    dims = list(struct.unpack_from(order + "8h", header, 40))
    pixdim = list(struct.unpack_from(order + "8f", header, 76))
    b, c, d = struct.unpack_from(order + "3f", header, 256)
    qoffset = list(struct.unpack_from(order + "3f", header, 268))
    srow = [list(struct.unpack_from(order + "4f", header, 280 + 16 * r)) for r in range(3)]
    shift = -(factor - 1) / (2.0 * factor)  # in old voxels along each axis
    # qform: rotation (quaternion) times diag(pixdim, qfac), qfac the sign of pixdim[0].
    a = max(0.0, 1.0 - b * b - c * c - d * d) ** 0.5
    rotation = [[a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)],
                [2 * (b * c + a * d), a * a + c * c - b * b - d * d, 2 * (c * d - a * b)],
                [2 * (b * d - a * c), 2 * (c * d + a * b), a * a + d * d - b * b - c * c]]
    scale = [pixdim[1], pixdim[2], pixdim[3] * (-1.0 if pixdim[0] < 0 else 1.0)]
    for r in range(3):
        qoffset[r] += shift * sum(rotation[r][k] * scale[k] for k in range(3))
        srow[r][3] += shift * sum(srow[r][:3])
        srow[r][:3] = [x / factor for x in srow[r][:3]]
    for axis in (1, 2, 3):
        if dims[axis] * factor > 32767:
            raise ValueError("%d x %d voxels do not fit a NIfTI-1 size" % (dims[axis], factor))
        dims[axis] *= factor
        pixdim[axis] /= factor
    struct.pack_into(order + "8h", header, 40, *dims)
    struct.pack_into(order + "8f", header, 76, *pixdim)
    struct.pack_into(order + "3f", header, 268, *qoffset)
    for r in range(3):
        struct.pack_into(order + "4f", header, 280 + 16 * r, *srow[r])
    return header


def upsample_nifti(source, target, factor):
    """Writes source upsampled factor times per axis by nearest neighbour as uncompressed NIfTI,
    one slice at a time (a 4x brain is 471 M voxels): x by strided array assignment, y by
    repeating rows, z by writing the slice factor times."""
    with open_nifti(source) as src, open(target, "wb") as dst:
        header, order = read_nifti_header(src)
        nx, ny, nz = struct.unpack_from(order + "3h", header, 42)
        size = struct.unpack_from(order + "h", header, 72)[0] // 8
        code = next(t for t in "BHILQ" if array.array(t).itemsize == size)  # copies bytes: any type of that size
        header = upsampled_header(header, order, factor)
        dst.write(header)
        row = nx * factor * size
        for _ in range(nz):
            plane = array.array(code, src.read(nx * ny * size))
            if len(plane) != nx * ny:
                raise ValueError("%s ends early" % source)
            wide = array.array(code, bytes(len(plane) * factor * size))
            for k in range(factor):
                wide[k::factor] = plane
            wide = wide.tobytes()
            slab = b"".join(wide[y * row:(y + 1) * row] * factor for y in range(ny))
            for _ in range(factor):
                dst.write(slab)


def run_scaling(options, cli):
    """cbc3d on the brain at each factor and thread count: a list of figures."""
    runs = []
    memory_limit = available_memory_bytes()
    with tempfile.TemporaryDirectory() as work:
        for factor in options.factors:
            path = os.path.join(SHARED, SCALING_IMAGE)
            if factor != 1:
                progress("upsampling %s %dx per axis" % (SCALING_IMAGE, factor))
                path = os.path.join(work, "brain-%dx.nii" % factor)
                upsample_nifti(os.path.join(SHARED, SCALING_IMAGE), path, factor)
            voxels = voxel_count(path)
            for threads in options.threads:
                progress("cbc3d on the brain %dx, %d thread%s" % (factor, threads, "s" if threads > 1 else ""))
                r = run_cbc3d(cli, path, 0, options.iterations, work, threads, memory_limit)
                runs.append(dict(r, factor=factor, threads=threads, voxels=voxels))
            if factor != 1:
                os.remove(path)
    return runs


def print_scaling(runs):
    """Speed-up: 1 thread's total over this run's, same image. Time and memory / 1x: against the
    original brain at the same thread count."""
    def find(factor, threads):
        return next((r for r in runs if r["factor"] == factor and r["threads"] == threads and "error" not in r), None)
    rows = []
    for r in runs:
        head = ["%dx" % r["factor"], "{:,}".format(r["voxels"]), "%d" % r["threads"]]
        if "error" in r:
            rows.append(head + ["failed: " + r["error"]] + [""] * 12)
            continue
        single, base = find(r["factor"], 1), find(1, r["threads"])
        total = r["seconds"]["total"]
        rows.append(head + ["%d" % r["tetrahedra"], "%.2f" % r["hausdorff_mm"]] + stage_cells(r) + [
            "%.0f" % r["peak_mb"],
            "%.2f" % (single["seconds"]["total"] / total) if single else "",
            "%.2f" % (total / base["seconds"]["total"]) if base else "",
            "%.2f" % (r["peak_mb"] / base["peak_mb"]) if base else ""])
    print("Scaling: %s upsampled per axis (nearest neighbour, same world extent), cbc3d with the paper's "
          "settings. Speed-up: against 1 thread on the same image; time and memory / 1x: against the "
          "original image at the same thread count." % SCALING_IMAGE)
    print()
    print_table(["brain", "voxels", "threads", "tets", "HD mm"] + list(STAGES) +
                ["total s", "peak MB", "speed-up", "time / 1x", "memory / 1x"], rows)


def describe_cgal(cgal, no_cgal):
    if cgal:
        return "CGAL Mesh_3: %s" % CGAL_SETTINGS
    if no_cgal:
        return "CGAL Mesh_3 left out (--no-cgal): cbc3d alone"
    return "CGAL Mesh_3 peer not built (install libcgal-dev, then configure and build again): cbc3d alone"


# The paper's Table 1: the nidus's target points per non-connectivity pattern, and its
# Hausdorff distance after 10 iterations (a Hausdorff metric it does not define; 1.79 mm before
# deformation) and seconds (Intel i7-2600).
PAPER_TABLE_1 = {"vertex": (2770, 0.97, 21.01), "edge": (3498, 0.91, 22.57), "face": (6213, 0.88, 26.19),
                 "none": (11755, 0.84, 35.27)}


def run_table1(cli):
    """cbc3d on the nidus with each pattern and 10 iterations, as in the paper's Table 1."""
    rows = {}
    with tempfile.TemporaryDirectory() as work:
        for pattern in PAPER_TABLE_1:
            progress("cbc3d on cbc3d-nidus.nii.gz, pattern %s, 10 iterations" % pattern)
            rows[pattern] = run_cbc3d(cli, os.path.join(SHARED, "cbc3d-nidus.nii.gz"), 0, "10", work,
                                      extra=["--pattern", pattern])
    return rows


def print_table1(rows):
    print("The paper's Table 1 on cbc3d-nidus.nii.gz, 10 iterations (the paper's Hausdorff metric there "
          "is not defined; cbc3d's is the paper's case-study definition):")
    print()
    table = []
    for pattern, r in rows.items():
        targets, paper_hd, paper_seconds = PAPER_TABLE_1[pattern]
        paper = ["%d" % targets, "%.2f" % paper_hd, "%.2f" % paper_seconds]
        if "error" in r:
            table.append([pattern] + paper + ["failed: " + r["error"], "", "", ""])
            continue
        table.append([pattern] + paper + ["%d" % r["deformation"]["targets"], "%.2f (%.2f, %.2f)" % (
            r["hausdorff_mm"], r["hausdorff_95_mm"], r["mean_distance_mm"]), "%.2f" % r["seconds"]["deformation"],
            "%d" % r["deformation"]["iterations"]])
    print_table(["pattern", "paper targets", "paper HD mm", "paper s", "cbc3d targets", "cbc3d HD mm (95%, mean)",
                 "cbc3d deformation s", "iterations done"], table)


def curve_point(r, seconds):
    """What a curve needs of one run; a failed run keeps its reason."""
    if "error" in r:
        return {"error": r["error"]}
    return {"tetrahedra": r["tetrahedra"], "points": r["points"], "hausdorff_mm": r["hausdorff_mm"],
            "hausdorff_95_mm": r["hausdorff_95_mm"], "mean_distance_mm": r["mean_distance_mm"],
            "min_dihedral_deg": r["min_dihedral_deg"], "max_dihedral_deg": r["max_dihedral_deg"],
            "seconds": seconds, "wall_seconds": r["wall_seconds"], "peak_mb": r["peak_mb"],
            "tissue_hausdorff_mm": {label: t["hausdorff_mm"] for label, t in r["tissues"].items()},
            "stage_seconds": r["seconds"] if isinstance(r["seconds"], dict) else None}


def cbc3d_curve(options, cli, path, background, work):
    """cbc3d at each tet budget (size_curves.py); seconds = its whole run."""
    def run(settings):
        return run_cbc3d(cli, path, background, options.iterations, work, settings=settings)
    points = []
    for r in size_curves.budget_curve(run, options.curve_budgets, progress):
        point = dict(curve_point(r, r.get("seconds", {}).get("total")), budget=r["budget"], fidelity=r["fidelity"])
        points.append(point)
        progress("    " + point_text(point))
    return points


def cgal_size_options(factor):
    return ["--facet-size", "%g" % (CGAL_SIZES[0] * factor), "--facet-distance", "%g" % (CGAL_SIZES[1] * factor),
            "--cell-size", "%g" % (CGAL_SIZES[2] * factor)]


def cgal_curve(options, cgal, path, background, work):
    """CGAL at each factor, coarse to fine, with no time limits (tets, HD and seconds do not depend
    on the load) and, unless --no-curve-cgal-default, by default (its seconds are what a user
    waits). A factor whose predicted no-time-limit seconds exceed --curve-cgal-limit is skipped,
    and so are the finer ones: the prediction scales the last run's seconds by the cube of the
    size ratio (tets grow so where the cell size rules; fewer where the surface does)."""
    points, last = [], None
    for factor in sorted(options.curve_cgal_factors, reverse=True):
        point = {"factor": factor, "sizes_mm": [s * factor for s in CGAL_SIZES]}
        if last and options.curve_cgal_limit > 0:
            predicted = last[1] * (last[0] / factor) ** 3
            if predicted > options.curve_cgal_limit:
                progress("  CGAL x%g skipped: predicted %.0f s > %g s" % (factor, predicted, options.curve_cgal_limit))
                points.append(dict(point, skipped="predicted %.0f s > limit %g s" % (predicted, options.curve_cgal_limit)))
                continue
        progress("  CGAL x%g, no time limits" % factor)
        r = run_cgal(cgal, path, background, work, True, cgal_size_options(factor))
        point.update(curve_point(r, r.get("seconds")))
        progress("    " + point_text(point))
        if not options.no_curve_cgal_default and "error" not in r:
            progress("  CGAL x%g, default" % factor)
            d = run_cgal(cgal, path, background, work, False, cgal_size_options(factor))
            point["default"] = curve_point(d, d.get("seconds"))
            progress("    " + point_text(point["default"]))
        points.append(point)
        if "error" not in r:
            last = (factor, r["seconds"])
    return points


def point_text(point):
    if "error" in point:
        return "failed: " + point["error"]
    figure = lambda key: "-" if point.get(key) is None else "%.2f" % point[key]
    return "%d tets, HD %s mm (95%% %s), %s s" % (
        point["tetrahedra"], figure("hausdorff_mm"), figure("hausdorff_95_mm"), figure("seconds"))


def run_curves(options, images, cli, cgal):
    """Both curves on each image; after each image the JSON and its plot are written, so that an
    interrupted run keeps what it measured."""
    pyplot = import_pyplot() if options.plots else None
    figures = {"settings": {"cbc3d": " ".join(PAPER_SETTINGS[2:] + ["--iterations", options.iterations]),
                            "cgal": CGAL_SETTINGS if cgal else None,
                            "cgal_limit_s": options.curve_cgal_limit},
               "machine": {"cpus": os.cpu_count()}, "curves": {}}
    start = time.monotonic()
    with tempfile.TemporaryDirectory() as work:
        for name, background in images:
            path = os.path.join(SHARED, name)
            progress("curves on %s" % name)
            entry = figures["curves"][name] = {"cbc3d": cbc3d_curve(options, cli, path, background, work)}
            if cgal:
                entry["cgal"] = cgal_curve(options, cgal, path, background, work)
            figures["wall_seconds"] = time.monotonic() - start
            with open(options.json, "w") as out:
                json.dump(figures, out, indent=2)
            if pyplot:
                progress("  plot %s" % plot_curves(pyplot, name, entry, options.plots))
    return figures


def import_pyplot():
    """matplotlib with the Agg backend (no display), or None and one line saying so."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as pyplot
        return pyplot
    except ImportError:
        print("matplotlib is missing (Debian: apt-get install python3-matplotlib, then /usr/bin/python3): "
              "no plots", file=sys.stderr)
        return None


def measured(points, key):
    """The points that ran and have key, in the order given: coarse to fine, so that a curve
    that turns back (more tets at a coarser size) shows it."""
    return [p for p in points if "tetrahedra" in p and p.get(key) is not None]


def draw_series(axis, points, key, style, label, tags, **line):
    done = measured(points, key)
    if not done:
        return
    axis.plot([p["tetrahedra"] for p in done], [p[key] for p in done], style, label=label, **line)
    for (x, y), text in (merged_tags(done, key, tags) if tags else []):
        axis.annotate(text, (x, y), textcoords="offset points", xytext=(3, 3), fontsize=7)


def merged_tags(points, key, tags):
    """One tag per spot: points within 5% of each other in tets and value (the nidus meshes the
    same at 4, 8 and 16 mm) share a tag "4/8/16" instead of overprinting it."""
    spots = []
    for p in points:
        x, y = p["tetrahedra"], p[key]
        near = next((s for s in spots if abs(x / s[0][0] - 1) < 0.05 and abs(y / s[0][1] - 1) < 0.05), None)
        if near:
            near[1].append(tags(p))
        else:
            spots.append(((x, y), [tags(p)]))
    return [(spot, "/".join(texts)) for spot, texts in spots]


def plain_number(value):
    """20 rather than 2 x 10^1; 100k and 1M rather than 1e+05 and 1e+06."""
    if value >= 1e6:
        return "%gM" % (value / 1e6)
    return "%gk" % (value / 1e3) if value >= 1e4 else "%g" % value


def plain_log_ticks(ticks, low, high):
    """Plain numbers on a log axis; between powers of ten, 2 and 5 are labelled where the axis spans
    under two decades and 2 to 6 and 8 under one, so that a short axis has more than one label."""
    from matplotlib.ticker import FuncFormatter, NullFormatter
    ticks.set_major_formatter(FuncFormatter(lambda value, _: plain_number(value)))
    if high / low >= 100:
        ticks.set_minor_formatter(NullFormatter())
        return
    labelled = (2, 3, 4, 5, 6, 8) if high / low < 10 else (2, 5)
    def minor(value, _):
        mantissa = value / 10 ** math.floor(math.log10(value) + 1e-9)
        whole = round(mantissa)
        return plain_number(value) if whole in labelled and abs(mantissa - whole) < 1e-6 else ""
    ticks.set_minor_formatter(FuncFormatter(minor))


def plot_curves(pyplot, name, entry, folder):
    """One PNG per image: HD (max solid, 95th percentile dashed) and seconds against tets, log
    axes. cbc3d's points are tagged with the lattice size, CGAL's with the factor."""
    figure, (hd, seconds) = pyplot.subplots(1, 2, figsize=(10, 4))
    ours = sorted(entry["cbc3d"], key=lambda p: p["budget"])
    theirs = sorted(entry.get("cgal", []), key=lambda p: -p["factor"])
    cgal_default = [dict(p["default"], factor=p["factor"]) for p in theirs if "tetrahedra" in p.get("default", {})]
    ours_tag = lambda p: "%gk" % (p["budget"] / 1000.0)
    theirs_tag = lambda p: "x%g" % p["factor"]
    draw_series(hd, ours, "hausdorff_mm", "o-C0", "cbc3d (tag: --max-tets)", ours_tag)
    draw_series(hd, ours, "hausdorff_95_mm", "o--C0", None, None, mfc="none")
    draw_series(hd, theirs, "hausdorff_mm", "s-C3", "CGAL no time limits (tag: size factor)", theirs_tag)
    draw_series(hd, theirs, "hausdorff_95_mm", "s--C3", None, None, mfc="none")
    draw_series(seconds, ours, "seconds", "o-C0", "cbc3d (whole run)", ours_tag)
    draw_series(seconds, theirs, "seconds", "s-C3", "CGAL no time limits (make_mesh_3)", theirs_tag)
    draw_series(seconds, cgal_default, "seconds", "s:C1", "CGAL default (make_mesh_3)", None, mfc="none")
    hd.set_title("Hausdorff distance: max (solid), 95th percentile (dashed)", fontsize=9)
    seconds.set_title("seconds (lower is faster)", fontsize=9)
    # Legends where the curves cannot be: few tets with a small HD, few tets taking long.
    for axis, what, corner in ((hd, "Hausdorff distance (mm)", "lower left"), (seconds, "seconds", "upper left")):
        axis.set_xscale("log")
        axis.set_yscale("log")
        plain_log_ticks(axis.xaxis, *axis.get_xlim())
        plain_log_ticks(axis.yaxis, *axis.get_ylim())
        axis.set_xlabel("tetrahedra")
        axis.set_ylabel(what)
        axis.grid(True, which="both", alpha=0.3)
        axis.legend(fontsize=7, loc=corner)
    figure.suptitle(name)
    figure.tight_layout()
    os.makedirs(folder, exist_ok=True)
    target = os.path.join(folder, "curves-%s.png" % name.split(".")[0])
    figure.savefig(target, dpi=100)
    pyplot.close(figure)
    return target


def redraw_curves(options, images):
    """The table and plots of an earlier run, for the images asked."""
    with open(options.curves_from) as source:
        figures = json.load(source)
    names = [name for name, _ in images]
    figures["curves"] = {name: entry for name, entry in figures["curves"].items() if name in names}
    pyplot = import_pyplot() if options.plots else None
    for name, entry in figures["curves"].items() if pyplot else ():
        progress("plot %s" % plot_curves(pyplot, name, entry, options.plots))
    print_curves(figures)
    return 0


def print_curves(figures):
    """Every point as a Markdown row: cbc3d by lattice size, CGAL by factor (no time limits, with
    the default run's seconds and tets beside)."""
    rows = []
    for name, entry in figures["curves"].items():
        for p in entry["cbc3d"]:
            rows.append(curve_row(name, "cbc3d", "--max-tets %d (F %g)" % (p["budget"], p["fidelity"]), p) + ["", ""])
        for p in entry.get("cgal", []):
            size = "x%g (%s mm)" % (p["factor"], " / ".join("%g" % s for s in p["sizes_mm"]))
            d = p.get("default", {})
            rows.append(curve_row(name, "CGAL", size, p) + (
                ["%.2f" % d["seconds"], "%d" % d["tetrahedra"]] if "tetrahedra" in d else ["", ""]))
    print("Size curves: cbc3d at each tet budget (%s; fidelity 0.99 where 0.95 stops short); CGAL Mesh_3 at multiples of the paper's facet size, "
          "facet distance and cell size (%s), no time limits; seconds: cbc3d's whole run, CGAL's make_mesh_3. "
          "Whole curves run: %.0f s." % (figures["settings"]["cbc3d"], CGAL_SETTINGS, figures.get("wall_seconds", 0)))
    print()
    print_table(["image", "mesher", "size", "tets", "HD max mm", "HD 95% mm", "mean mm", "seconds", "peak MB",
                 "CGAL default s", "CGAL default tets"], rows)
    equal = []
    for name, entry in figures["curves"].items():
        equal += size_curves.equal_size_rows(name, entry["cbc3d"], entry.get("cgal", []))
    if equal:
        print()
        print("cbc3d against CGAL (no time limits) at cbc3d's tets, CGAL interpolated along its curve:")
        print()
        print_table(size_curves.EQUAL_SIZE_HEADER, equal)


def curve_row(name, mesher, size, p):
    if "skipped" in p:
        return [name, mesher, size, "skipped: " + p["skipped"]] + [""] * 5
    if "error" in p:
        return [name, mesher, size, "failed: " + p["error"]] + [""] * 5
    figure = lambda key, form="%.2f": "-" if p.get(key) is None else form % p[key]
    return [name, mesher, size, "%d" % p["tetrahedra"], figure("hausdorff_mm"), figure("hausdorff_95_mm"),
            figure("mean_distance_mm"), figure("seconds"), figure("peak_mb", "%.0f")]


def main():
    options = parse_arguments()
    candidates = IMAGES + CURVE_HEADS if options.curves or options.curves_from else IMAGES
    images = [(name, background) for name, background in candidates
              if not options.images or any(part in name for part in options.images)]
    if not images:
        print("no image of %s matches %s" % (", ".join(name for name, _ in IMAGES), " ".join(options.images)))
        return 1
    if options.curves_from:  # needs neither the images nor a build
        return redraw_curves(options, images)
    if not os.path.isdir(SHARED):
        print("skipped: no ../shared/data beside the checkout")
        return 0
    cli = os.path.join(options.build, "bin", "cbc3d")
    if not os.path.exists(cli):
        print("no %s: build first (cmake -S . -B build && cmake --build build)" % cli)
        return 1
    cgal = os.path.join(options.build, "bin", "CBC3DCGALMesh3")
    if options.no_cgal or not os.path.exists(cgal):
        cgal = None
    figures = {"machine": {"cpus": os.cpu_count(), "memory_available_mb": (available_memory_bytes() or 0) / 2**20},
               "settings": {"cbc3d": " ".join(PAPER_SETTINGS + ["--iterations", options.iterations]),
                            "cgal": CGAL_SETTINGS if cgal else None}}
    if options.curves:
        figures = run_curves(options, images, cli, cgal)
        print(describe_cgal(cgal, options.no_cgal))
        print()
        print_curves(figures)
        print("figures written to %s" % options.json)
        return 0
    print("cbc3d %s --iterations %s" % (" ".join(PAPER_SETTINGS), options.iterations))
    if not options.scaling_only:
        print(describe_cgal(cgal, options.no_cgal))
    print()
    if not options.scaling_only:
        figures["images"] = mesh_images(options, images, cli, cgal)
        print_comparison(figures["images"], options.cgal_runs)
        print_stages(figures["images"])
        print_tissues(figures["images"])
        print_topology(figures["images"])
        figures["table1"] = run_table1(cli)
        print_table1(figures["table1"])
    if not options.no_scaling:
        figures["scaling"] = run_scaling(options, cli)
        print_scaling(figures["scaling"])
    if not options.scaling_only and not options.no_targets:
        figures["targets"] = speed_targets.measure(cli, SHARED, PAPER_SETTINGS, figures["images"],
                                                   read_nifti_header, open_nifti, upsample_nifti, progress)
        speed_targets.print_targets(figures["targets"], print_table)
    with open(options.json, "w") as out:
        json.dump(figures, out, indent=2)
    print("figures written to %s" % options.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
