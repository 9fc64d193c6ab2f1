"""The speed issue's targets, each measured in this run as a ratio of two runs on this machine.

- against CGAL Mesh_3's default runs (their make_mesh_3 seconds over cbc3d's whole run):
  at least 10 on the brain and the two heads, at least 1 on the nidus and the ventricles;
- two threads against one on the brain (wall seconds): at least 1.7;
- the brain upsampled 4x per axis against the brain (wall seconds, 2 threads): at most 8, with a
  peak of at most 2.5 GB;
- the brain padded with background to 4 times its voxels against the brain (CPU seconds, 1
  thread): at most 1.2;
- the brain with a 200 mm lattice against the 8 mm one (CPU seconds, 1 thread): at most 1.

Each pair of runs alternates, RUNS times, and the medians are compared, so that a change in
the machine's load hits both sides. Nothing is asserted: the table says which targets are met.
"""
import os
import statistics
import struct
import subprocess
import tempfile
import time

RUNS = 3
CGAL_GOALS = {"cbc3d-brain.nii.gz": 10.0, "nipype-tissue-labels.nii.gz": 10.0,
              "itk-t1-kmeans-labels.nii.gz": 10.0, "cbc3d-nidus.nii.gz": 1.0, "cbc3d-ventricles.nii.gz": 1.0}
BRAIN = "cbc3d-brain.nii.gz"
COARSE_LATTICE_MM = "200"  # the brain is 246 mm across: cbc3d refuses a lattice wider than that


def timed_run(command):
    """Wall and CPU seconds (user + system) and peak resident MB of one run; raises on failure."""
    with tempfile.TemporaryFile("w+") as err:
        start = time.monotonic()
        process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.monotonic() - start
        if os.waitstatus_to_exitcode(status) != 0:
            err.seek(0)
            raise RuntimeError("%s failed: %s" % (" ".join(command), err.read().strip()[-300:]))
    return {"wall": wall, "cpu": usage.ru_utime + usage.ru_stime, "peak_mb": usage.ru_maxrss / 1024.0}


def alternate(first, second):
    """Medians of RUNS alternating runs of two commands: (first's, second's) figures."""
    runs = ([], [])
    for _ in range(RUNS):
        runs[0].append(timed_run(first))
        runs[1].append(timed_run(second))
    return tuple({key: statistics.median(r[key] for r in side) for key in ("wall", "cpu", "peak_mb")}
                 for side in runs)


def pad_nifti(read_header, open_nifti, source, target, factor):
    """Writes source with background (zero) voxels added at the high end of each axis, so that it
    holds at least `factor` times the voxels; the world frame stays where it was."""
    with open_nifti(source) as src:
        header, order = read_header(src)
        data = src.read()
    nx, ny, nz = struct.unpack_from(order + "3h", header, 42)
    size = struct.unpack_from(order + "h", header, 72)[0] // 8
    grow = factor ** (1.0 / 3.0)
    mx, my, mz = (int(-(-n * grow // 1)) for n in (nx, ny, nz))
    struct.pack_into(order + "3h", header, 42, mx, my, mz)
    row, pad_row = nx * size, (mx - nx) * size
    with open(target, "wb") as dst:
        dst.write(header)
        empty_plane_rows = bytes(mx * size) * (my - ny)
        for z in range(nz):
            plane = data[z * nx * ny * size:(z + 1) * nx * ny * size]
            dst.write(b"".join(plane[y * row:(y + 1) * row] + bytes(pad_row) for y in range(ny)))
            dst.write(empty_plane_rows)
        dst.write(bytes(mx * my * size) * (mz - nz))
    return nx * ny * nz, mx * my * mz


def cgal_rows(images):
    rows = []
    for name, entry in images.items():
        ours, runs = entry.get("cbc3d", {}), entry.get("cgal_default", [])
        cgal = [r["seconds"] for r in runs if "error" not in r]
        if name in CGAL_GOALS and cgal and "error" not in ours:
            ratio = statistics.median(cgal) / ours["seconds"]["total"]
            rows.append(("CGAL default s / cbc3d s, %s" % name, ratio, ">= %g" % CGAL_GOALS[name],
                         ratio >= CGAL_GOALS[name], "%.2f / %.2f s" % (statistics.median(cgal), ours["seconds"]["total"])))
    return rows


def thread_row(base):
    one, two = alternate(base + ["--threads", "1"], base + ["--threads", "2"])
    ratio = one["wall"] / two["wall"]
    return ("brain: 1 thread / 2 threads (wall)", ratio, ">= 1.7", ratio >= 1.7,
            "%.2f / %.2f s" % (one["wall"], two["wall"]))


def padding_row(base, brain, work, read_header, open_nifti):
    padded = os.path.join(work, "brain-padded.nii")
    voxels, padded_voxels = pad_nifti(read_header, open_nifti, brain, padded, 4)
    plain, pad = alternate(base + ["--threads", "1"], [base[0], padded] + base[2:] + ["--threads", "1"])
    os.remove(padded)
    ratio = pad["cpu"] / plain["cpu"]
    return ("brain padded to %.1fx voxels / brain (CPU, 1 thread)" % (padded_voxels / voxels), ratio, "<= 1.2",
            ratio <= 1.2, "%.2f / %.2f s; peak %.0f / %.0f MB" % (pad["cpu"], plain["cpu"], pad["peak_mb"], plain["peak_mb"]))


def lattice_row(base, paper_settings):
    coarse_settings = list(paper_settings)
    coarse_settings[coarse_settings.index("--bcc-size") + 1] = COARSE_LATTICE_MM
    fine, coarse = alternate(base + ["--threads", "1"], base[:5] + coarse_settings + ["--threads", "1"])
    ratio = coarse["cpu"] / fine["cpu"]
    return ("brain: %s mm lattice / 8 mm (CPU, 1 thread)" % COARSE_LATTICE_MM, ratio, "<= 1", ratio <= 1.0,
            "%.2f / %.2f s" % (coarse["cpu"], fine["cpu"]))


def scaling_rows(base, brain, work, upsample):
    """The 4x brain against the brain, both at 2 threads. The 4x image is written once, before
    the runs: a single run right after writing it would time the disk (this VM keeps little of a
    471 MB file in its page cache) as much as the meshing."""
    big = os.path.join(work, "brain-4x.nii")
    upsample(brain, big, 4)
    try:
        small, large = alternate(base + ["--threads", "2"], [base[0], big] + base[2:] + ["--threads", "2"])
    finally:
        os.remove(big)
    ratio = large["wall"] / small["wall"]
    peak = large["peak_mb"] / 1024.0
    return [("brain 4x per axis / brain (wall, 2 threads)", ratio, "<= 8", ratio <= 8.0,
             "%.2f / %.2f s" % (large["wall"], small["wall"])),
            ("brain 4x per axis: peak GB", peak, "<= 2.5", peak <= 2.5, "")]


def measure(cli, shared, paper_settings, images, read_header, open_nifti, upsample, progress):
    """Every target's figures: a list of {target, measured, goal, met, detail}; a target whose runs
    failed says why in its detail."""
    rows = cgal_rows(images)
    brain = os.path.join(shared, BRAIN)
    with tempfile.TemporaryDirectory() as work:
        base = [cli, brain, "-o", os.path.join(work, "mesh.vtu"), "--quiet"] + paper_settings
        steps = [("the brain with 1 and 2 threads", "brain: 1 thread / 2 threads", lambda: [thread_row(base)]),
                 ("the brain padded with background", "brain padded / brain",
                  lambda: [padding_row(base, brain, work, read_header, open_nifti)]),
                 ("the brain with a %s mm lattice" % COARSE_LATTICE_MM, "brain: coarse lattice / 8 mm",
                  lambda: [lattice_row(base, paper_settings)]),
                 ("the brain upsampled 4x per axis", "brain 4x per axis / brain",
                  lambda: scaling_rows(base, brain, work, upsample))]
        for text, name, step in steps:
            progress("speed targets: " + text)
            try:
                rows += step()
            except (RuntimeError, OSError, ValueError) as error:
                rows.append((name, None, "", False, "failed: %s" % error))
    return [{"target": name, "measured": value, "goal": goal, "met": met, "detail": detail}
            for name, value, goal, met, detail in rows]


def print_targets(rows, print_table):
    print("The speed issue's targets, as ratios of runs made side by side in this run (medians of %d "
          "alternating runs where cbc3d runs twice):" % RUNS)
    print()
    print_table(["target", "measured", "goal", "met", "runs"],
                [[r["target"], "-" if r["measured"] is None else "%.2f" % r["measured"], r["goal"], "yes" if r["met"] else "no", r["detail"]]
                 for r in rows])
