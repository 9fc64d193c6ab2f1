#!/usr/bin/env python3
"""Throughput, memory, threads and CGAL targets of cbc3d on the real images of ../shared/data.

Prints Markdown tables that a benchmark record can quote as they are:

- each image meshed at the CLI's defaults (no size options) with 2 threads: tets, wall seconds,
  tets per second over the whole run, peak resident memory, bytes per tet, and the seconds of
  each stage from the run's --report; on the two New York Heads the targets of at least
  150,000 tets a second and at most 400 bytes per tet are marked met or not met;
- threads: RUNS alternating runs at 1 and 2 threads on the 1 mm head (or, without it, the image
  with the most tets), the ratio of the median wall seconds against 1.75;
- CGAL: RUNS alternating runs of cbc3d at the paper's settings and of CGAL Mesh_3's default run
  (its perturber's and exuder's time limits on) on the brain, the 3 mm head and the k-means head,
  the ratio of the median seconds against 10; both meshers get the k-means air (label 1) as
  background;
- with --plot, the seconds of each stage against tets on log axes, one marker per image, as a
  PNG (where matplotlib imports) and always as a CSV beside it; --plot-from CSV redraws it.

Alternating the runs of a pair lets a change in the machine's load hit both sides. Nothing is
asserted: the tables say which targets are met. Exits 0 with a message where the shared data
is missing.

    python3 Testing/Benchmark/throughput.py [BUILD_DIR] [--images NAME ...] [--runs N]
        [--plot PNG] [--skip-cgal] [--skip-threads]
    python3 Testing/Benchmark/throughput.py --plot-from CSV --plot PNG
"""
import argparse
import csv
import datetime
import json
import os
import statistics
import subprocess
import sys
import tempfile

import benchmark_meshing as meshing
import speed_targets

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
HEAD_1MM = "nyhead-6tissue-1mm.nii.gz"
HEADS = (HEAD_1MM, "nyhead-6tissue-0.5mm.nii.gz")
# The k-means head's label 1 is the air around it, meshed as background (benchmark_meshing.py).
BACKGROUNDS = dict(meshing.IMAGES)
IMAGES = [name for name, _ in meshing.IMAGES] + list(HEADS)
CGAL_IMAGES = ("cbc3d-brain.nii.gz", "nipype-tissue-labels.nii.gz", "itk-t1-kmeans-labels.nii.gz")
THREADS = "2"  # the targets are stated for 2 cores
TETS_PER_SECOND_GOAL = 150000.0
BYTES_PER_TET_GOAL = 400.0
THREADS_GOAL = 1.75
CGAL_GOAL = 10.0
PLOT_STAGES = meshing.STAGES + ("total",)
MARKERS = "osv^DPX<>*hp"


def parse_arguments():
    parser = argparse.ArgumentParser(description="cbc3d's throughput, memory, threads and CGAL targets")
    parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"),
                        help="build folder, or the path of its bin/cbc3d (default: build)")
    parser.add_argument("--images", nargs="+", metavar="NAME",
                        help="only the images whose file name contains one of these (default: all seven)")
    parser.add_argument("--runs", type=int, default=3,
                        help="alternating runs of each side of a ratio; the medians are compared (default 3)")
    parser.add_argument("--plot", metavar="PNG", help="draw seconds per stage against tets here (and a CSV beside it)")
    parser.add_argument("--plot-from", metavar="CSV", help="run nothing: draw --plot from an earlier run's CSV")
    parser.add_argument("--skip-cgal", action="store_true", help="no CGAL comparison")
    parser.add_argument("--skip-threads", action="store_true", help="no 1-thread against 2-thread runs")
    options = parser.parse_args()
    if options.runs < 1:
        parser.error("--runs must be at least 1")
    if options.plot_from and not options.plot:
        parser.error("--plot-from needs --plot PNG")
    if os.path.basename(options.build) == "cbc3d":  # a path to the binary also works
        options.build = os.path.dirname(os.path.dirname(options.build))
    return options


def shared_folder():
    return os.environ.get("CBC3D_SHARED_DATA") or os.path.join(ROOT, "..", "shared", "data")


def progress(text):
    print(text, file=sys.stderr, flush=True)


def command_output(command):
    try:
        return subprocess.run(command, capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def proc_field(path, key):
    """The value of the first "key: value" line of a /proc file, or None."""
    try:
        with open(path) as lines:
            for line in lines:
                if line.split(":")[0].strip() == key:
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return None


def print_provenance(cli):
    """What a record needs to cite the run: when, which commit, which binary, which machine."""
    memory_kb = proc_field("/proc/meminfo", "MemTotal")
    memory = "%.1f GiB" % (int(memory_kb.split()[0]) / 2**20) if memory_kb else "unknown memory"
    print("- date: %s" % datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z"))
    print("- commit: %s" % command_output(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"]))
    print("- cbc3d: %s (%s)" % (cli, command_output([cli, "--version"])))
    print("- machine: %s cores (%d usable here), %s, %s" % (
        os.cpu_count(), len(os.sched_getaffinity(0)), proc_field("/proc/cpuinfo", "model name") or "unknown CPU",
        memory))
    print()


def defaults_command(cli, path, work, threads, report=None):
    """cbc3d at its defaults: no size option, only the background, the threads and the outputs."""
    command = [cli, path, "-o", os.path.join(work, "mesh.vtu"), "--background", str(BACKGROUNDS.get(
        os.path.basename(path), 0)), "--threads", threads, "--quiet"]
    return command + (["--report", report] if report else [])


def run_defaults(cli, path, work):
    """One run at the defaults with 2 threads: its --report figures plus wall_seconds and
    peak_mb (the process's own peak resident size), or {"error": reason}."""
    report = os.path.join(work, "report.json")
    if os.path.exists(report):
        os.remove(report)
    code, _, err, seconds, peak = meshing.run_measured(defaults_command(cli, path, work, THREADS, report))
    if code != 0:
        return {"error": meshing.failure(code, err)}
    with open(report) as r:
        return dict(json.load(r), wall_seconds=seconds, peak_mb=peak)


def rates(r):
    """Tets a second over the whole run (the process's wall seconds: reading and writing
    included) and bytes of peak resident memory per tet."""
    return r["tetrahedra"] / r["wall_seconds"], r["peak_mb"] * 2**20 / r["tetrahedra"]


def met(ok):
    return "met" if ok else "not met"


def print_throughput(results):
    """The defaults table; returns the heads' target rows for the summary."""
    rows, targets = [], []
    for name, r in results.items():
        if "error" in r:
            rows.append([name, "failed: " + r["error"]] + [""] * 7)
            continue
        speed, memory = rates(r)
        marks = ["-", "-"]
        if name in HEADS:
            marks = [met(speed >= TETS_PER_SECOND_GOAL), met(memory <= BYTES_PER_TET_GOAL)]
            targets += [("%s: tets a second" % name, "%.0f" % speed, ">= %.0f" % TETS_PER_SECOND_GOAL,
                         speed >= TETS_PER_SECOND_GOAL, "%d tets in %.2f s" % (r["tetrahedra"], r["wall_seconds"])),
                        ("%s: peak bytes per tet" % name, "%.0f" % memory, "<= %.0f" % BYTES_PER_TET_GOAL,
                         memory <= BYTES_PER_TET_GOAL, "peak %.0f MB" % r["peak_mb"])]
        rows.append([name, "%d" % r["tetrahedra"], "%.2f" % r["wall_seconds"], "%.2f" % r["seconds"]["total"],
                     "%.0f" % speed, marks[0], "%.0f" % r["peak_mb"], "%.0f" % memory, marks[1]])
    print("cbc3d at its defaults with %s threads, one run per image. Tets a second: tets over the "
          "process's wall seconds (reading and writing included); bytes per tet: its peak resident "
          "memory over its tets. Targets on the two New York Heads:" % THREADS)
    print()
    meshing.print_table(["image", "tets", "wall s", "report total s", "tets / s", ">= 150,000",
                         "peak MB", "bytes / tet", "<= 400"], rows)
    return targets


def print_stages(results):
    rows = [[name, "%d" % r["tetrahedra"]] + ["%.2f" % r["seconds"][stage] for stage in PLOT_STAGES]
            for name, r in results.items() if "error" not in r]
    print("Seconds per stage of the same runs (from --report):")
    print()
    meshing.print_table(["image", "tets"] + list(PLOT_STAGES), rows)


def thread_target(cli, path, work):
    """Median wall seconds of alternating 1-thread and 2-thread runs at the defaults."""
    one, two = speed_targets.alternate(defaults_command(cli, path, work, "1"),
                                       defaults_command(cli, path, work, "2"))
    ratio = one["wall"] / two["wall"]
    return ("%s: 1 thread / 2 threads (wall s)" % os.path.basename(path), "%.2f" % ratio,
            ">= %.2f" % THREADS_GOAL, ratio >= THREADS_GOAL,
            "%.2f / %.2f s; CPU %.2f / %.2f s" % (one["wall"], two["wall"], one["cpu"], two["cpu"]))


def cgal_target(cli, cgal, path, work, runs):
    """cbc3d at the paper's settings (2 threads) against CGAL's default run, alternating. As in
    speed_targets.py, CGAL's seconds are make_mesh_3's alone (the peer's JSON "seconds", which
    leaves out its reading, measuring and writing and so favours CGAL), cbc3d's are its whole
    run (the report's total: reading, meshing, measuring, writing)."""
    name, background = os.path.basename(path), BACKGROUNDS.get(os.path.basename(path), 0)
    ours, theirs = [], []
    for run in range(runs):
        progress("CGAL target: %s, run %d of %d" % (name, run + 1, runs))
        ours.append(meshing.run_cbc3d(cli, path, background, "5", work, threads=THREADS))
        theirs.append(meshing.run_cgal(cgal, path, background, work, deterministic=False))
    failed = [r["error"] for r in ours + theirs if "error" in r]
    label = "%s: CGAL default s / cbc3d s (paper's settings)" % name
    if failed:
        return (label, "-", ">= %g" % CGAL_GOAL, False, "failed: " + failed[0])
    cbc3d_seconds = statistics.median(r["seconds"]["total"] for r in ours)
    cgal_seconds = statistics.median(r["seconds"] for r in theirs)
    ratio = cgal_seconds / cbc3d_seconds
    return (label, "%.2f" % ratio, ">= %g" % CGAL_GOAL, ratio >= CGAL_GOAL,
            "%.2f / %.2f s; tets %d / %d" % (cgal_seconds, cbc3d_seconds, statistics.median(
                r["tetrahedra"] for r in theirs), ours[0]["tetrahedra"]))


def write_stage_csv(results, path):
    with open(path, "w", newline="") as out:
        table = csv.writer(out)
        table.writerow(["image", "tets"] + list(PLOT_STAGES) + ["wall_seconds", "peak_mb"])
        for name, r in results.items():
            if "error" not in r:
                table.writerow([name, r["tetrahedra"]] + [r["seconds"][s] for s in PLOT_STAGES] +
                               [r["wall_seconds"], r["peak_mb"]])


def read_stage_csv(path):
    with open(path, newline="") as source:
        return {row["image"]: {"tetrahedra": int(row["tets"]), "seconds": {s: float(row[s]) for s in PLOT_STAGES}}
                for row in csv.DictReader(source)}


def short_name(name):
    return name.replace(".nii.gz", "").replace("cbc3d-", "").replace("nyhead-6tissue-", "New York Head ")


def draw_stages(results, path):
    """Seconds of each stage (a colour each, a line through its points in tets order) against
    tets, log-log, one marker per image. A stage that took 0 s has no place on a log axis."""
    pyplot = meshing.import_pyplot()
    if pyplot is None:
        return
    done = sorted(((name, r) for name, r in results.items() if "error" not in r),
                  key=lambda item: item[1]["tetrahedra"])
    figure, axis = pyplot.subplots(figsize=(9.5, 5.5))
    colours = pyplot.rcParams["axes.prop_cycle"].by_key()["color"]
    for index, stage in enumerate(PLOT_STAGES):
        points = [(r["tetrahedra"], r["seconds"][stage], n) for n, (_, r) in enumerate(done) if r["seconds"][stage] > 0]
        colour = colours[index % len(colours)]
        width = 2.0 if stage == "total" else 1.0
        axis.plot([p[0] for p in points], [p[1] for p in points], "-", color=colour, linewidth=width, label=stage)
        for tets, seconds, n in points:
            axis.plot(tets, seconds, MARKERS[n % len(MARKERS)], color=colour, markersize=6)
    axis.set_xscale("log")
    axis.set_yscale("log")
    meshing.plain_log_ticks(axis.xaxis, *axis.get_xlim())
    meshing.plain_log_ticks(axis.yaxis, *axis.get_ylim())
    axis.set_xlabel("tets")
    axis.set_ylabel("seconds")
    axis.set_title("cbc3d seconds per stage against tets (defaults, %s threads)" % THREADS)
    axis.grid(True, which="both", alpha=0.3)
    stages = axis.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, title="stage")
    axis.add_artist(stages)
    images = [axis.plot([], [], MARKERS[n % len(MARKERS)], color="grey", label=short_name(name))[0]
              for n, (name, _) in enumerate(done)]
    axis.legend(handles=images, loc="lower left", bbox_to_anchor=(1.01, 0), fontsize=8, title="image")
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    pyplot.close(figure)
    print("stage seconds drawn in %s" % path)


def print_summary(targets, runs):
    print("Targets: the heads' rates from the single runs above, the ratios from the medians of %d "
          "alternating run(s) of each side:" % runs)
    print()
    meshing.print_table(["target", "measured", "goal", "met", "runs"],
                        [[name, value, goal, met(ok), detail] for name, value, goal, ok, detail in targets])


def selected_images(options, shared):
    """The images asked for that are there, in the default order; a line for each missing one."""
    names = [n for n in IMAGES if not options.images or any(part in n for part in options.images)]
    present = [n for n in names if os.path.exists(os.path.join(shared, n))]
    for name in names:
        if name not in present:
            print("skipped: %s is not in %s" % (name, shared))
    return present


def measure_targets(options, cli, shared, results, work):
    """The threads and CGAL targets' rows, each a ratio of medians of alternating runs."""
    targets = []
    if not options.skip_threads and results:
        ran = [n for n, r in results.items() if "error" not in r]
        largest = HEAD_1MM if HEAD_1MM in results else max(ran, key=lambda n: results[n]["tetrahedra"], default=None)
        if largest:
            progress("threads target: %s, %d alternating runs at 1 and 2 threads" % (largest, options.runs))
            speed_targets.RUNS = options.runs
            try:
                targets.append(thread_target(cli, os.path.join(shared, largest), work))
            except RuntimeError as error:
                targets.append(("%s: 1 thread / 2 threads" % largest, "-", ">= %.2f" % THREADS_GOAL, False,
                                "failed: %s" % error))
    cgal = os.path.join(options.build, "bin", "CBC3DCGALMesh3")
    if not options.skip_cgal and not os.path.exists(cgal):
        print("CGAL target skipped: no %s (built only where Debian's libcgal-dev was installed before "
              "configuring)" % cgal)
        print()
    elif not options.skip_cgal:
        for name in (n for n in CGAL_IMAGES if n in results):
            targets.append(cgal_target(cli, cgal, os.path.join(shared, name), work, options.runs))
    return targets


def main():
    options = parse_arguments()
    if options.plot_from:
        draw_stages(read_stage_csv(options.plot_from), options.plot)
        return 0
    shared = shared_folder()
    if not os.path.isdir(shared):
        print("skipped: no shared data at %s (set CBC3D_SHARED_DATA)" % shared)
        return 0
    cli = os.path.join(options.build, "bin", "cbc3d")
    if not os.path.exists(cli):
        print("no %s: build first (cmake -S . -B build && cmake --build build)" % cli)
        return 1
    images = selected_images(options, shared)
    if not images:
        print("skipped: no image to run")
        return 0
    print_provenance(cli)
    results = {}
    with tempfile.TemporaryDirectory() as work:
        for name in images:
            progress("defaults: %s" % name)
            results[name] = run_defaults(cli, os.path.join(shared, name), work)
        targets = print_throughput(results)
        print_stages(results)
        targets += measure_targets(options, cli, shared, results, work)
    if targets:
        print_summary(targets, options.runs)
    if options.plot:
        csv_path = os.path.splitext(options.plot)[0] + ".csv"
        write_stage_csv(results, csv_path)
        print("stage seconds written to %s" % csv_path)
        draw_stages(results, options.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
