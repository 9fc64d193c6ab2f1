#!/usr/bin/env python3
"""cbc3d and CGAL Mesh_3 on a thin shell of coarse voxels, side by side.

    python3 Testing/Benchmark/thin_shell.py [BUILD] [--cgal-sizes 8,6,4,2] [--lattices ...]

The image is the topology phantoms test's skull-like shell: radii 25 to 27 voxels in a 64^3
image of 3.9 mm voxels, its surface two spheres (Euler characteristic 4). Issue 13 asks that
cbc3d's surface be never further from the image's Euler characteristic than CGAL's here.

cbc3d runs at its defaults and at several lattice sizes; CGAL's peer (CBC3DCGALMesh3, built
where Debian's libcgal-dev was installed before configuring) at facet size = facet distance =
cell size of each given size (2 mm with cell size 2.5 is the paper's), without time limits
and seeded on every component of the image (--seed-components: make_mesh_3's own start finds
no surface on a hollow shell and makes no mesh at all). Both are measured by cbc3d's quality
filter. Prints one Markdown table; without the peer, cbc3d's rows alone.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "Testing", "Python"))
from cbc3d_testing import write_nifti  # noqa: E402

SPACING = 3.9


def shell_image(path):
    index = np.arange(64) + 0.5
    x, y, z = np.meshgrid(index, index, index, indexing="ij")
    d = np.sqrt((x - 32) ** 2 + (y - 32) ** 2 + (z - 32) ** 2)
    shell = ((d > 25) & (d <= 27)).astype(np.int16)
    write_nifti(path, shell.shape, shell.transpose(2, 1, 0).ravel().tolist(), dtype="int16",
                pixdim=(1.0, SPACING, SPACING, SPACING))


def numbers(text):
    return [float(v) for v in text.split(",") if v]


def row(mesher, setting, figures, seconds):
    topology, tissue = figures["topology"], figures["tissues"]["1"]
    volume = 100.0 * tissue["volume_mm3"] / tissue["image_volume_mm3"]
    return "| %s | %s | %d | %d (%d) | %s | %d / %d | %.1f%% | %.2f | %.2f / %.2f | %.2f |" % (
        mesher, setting, figures["tetrahedra"], topology["surface_euler"], topology["image_surface_euler"],
        "yes" if topology["solver_ready"] else "no", topology["nonmanifold_edges"],
        topology["nonmanifold_vertices"], volume, figures["hausdorff_mm"], figures["min_dihedral_deg"],
        figures["max_dihedral_deg"], seconds)


def run(command):
    start = time.monotonic()
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit("%s failed (%d): %s" % (os.path.basename(command[0]), done.returncode, done.stderr.strip()))
    return done, time.monotonic() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"))
    parser.add_argument("--lattices", default="0,16,12,8,6,4",
                        help="cbc3d lattice sizes in mm, 0 for the defaults (default 0,16,12,8,6,4)")
    parser.add_argument("--cgal-sizes", default="8,6,4,2",
                        help="CGAL facet size = facet distance = cell size in mm; 2 is the paper's (cell 2.5)")
    options = parser.parse_args()
    cli = os.path.join(options.build, "bin", "cbc3d")
    cgal = os.path.join(options.build, "bin", "CBC3DCGALMesh3")
    if not os.path.exists(cli):
        raise SystemExit("no %s: build first" % cli)
    rows = []
    with tempfile.TemporaryDirectory() as work:
        image = os.path.join(work, "thin_shell.nii")
        shell_image(image)
        for size in numbers(options.lattices):
            setting = ["--bcc-size", "%g" % size] if size > 0 else []
            report = os.path.join(work, "cbc3d.json")
            _, seconds = run([cli, image, "-o", os.path.join(work, "cbc3d.vtu"), "--report", report, "--quiet"] + setting)
            with open(report) as f:
                rows.append(row("cbc3d", "lattice %g mm" % size if size > 0 else "defaults", json.load(f), seconds))
        if not os.path.exists(cgal):
            print("no CGAL peer (%s): install libcgal-dev and configure again for CGAL's rows" % cgal, file=sys.stderr)
        for size in numbers(options.cgal_sizes) if os.path.exists(cgal) else []:
            cell = 2.5 if size == 2 else size
            done, seconds = run([cgal, image, os.path.join(work, "cgal.vtu"), "--deterministic", "--seed-components",
                                 "--facet-size", "%g" % size, "--facet-distance", "%g" % size, "--cell-size", "%g" % cell])
            figures = json.loads(done.stdout.strip().splitlines()[-1])
            rows.append(row("CGAL Mesh_3", "facet %g, cell %g mm" % (size, cell), figures, figures["seconds"]))
    print("| mesher | setting | tets | surface Euler (image) | ready for a solver | non-manifold edges / vertices "
          "| volume / voxels' | HD mm | dihedral min / max | seconds |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    print("\n".join(rows))


if __name__ == "__main__":
    main()
