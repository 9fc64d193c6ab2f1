# Plain python3: random label images through the whole command-line pipeline (lattice,
# refinement, sound labels, deformation), each mesh checked by the independent numpy checker
# mesh_topology.py and by dihedral angles computed here:
#   - cbc3d exits 0;
#   - no hinged part and no non-manifold edge or vertex, in any tissue or in the whole mesh;
#   - every dihedral angle within [20, 160] degrees and every tet positively oriented.
# The images are voxel noise of 2 to 5 labels, some smoothed by a 3^3 or 5^3 majority (specks,
# thin sheets, pockets, diagonal contacts), 16 to 39 voxels a side, anisotropic spacing, at
# lattices of 2 to 8 spacings, with face or centre targets. The cbc3d of 2026-12-03 before
# sound labels on every input (Benchmarks.md, "Changes that alter meshes": 2026-12-03, 89d3a11) fails 4 of these 12 images (its manifold repair went round in cycles where
# the mesh itself pinches) and takes 130 s against 19 s.
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, dihedral_angles, signed_volumes, write_nifti  # noqa: E402
import mesh_topology as mt  # noqa: E402

IMAGES = 12
cli = os.environ["CBC3D_CLI"]
check = Checks()


def majority(noise, labels, radius):
    """Each voxel takes the most common label of its (2 radius + 1)^3 box (clamped at the edges)."""
    if radius == 0:
        return noise
    padded = np.pad(noise, radius, mode="edge")
    n = noise.shape[0]
    votes = np.zeros((labels,) + noise.shape, dtype=np.int32)
    for dx in range(2 * radius + 1):
        for dy in range(2 * radius + 1):
            for dz in range(2 * radius + 1):
                window = padded[dx:dx + n, dy:dy + n, dz:dz + n]
                for label in range(labels):
                    votes[label] += window == label
    return votes.argmax(axis=0)


def random_case(seed):
    """(image, spacing, cbc3d options) of one seed."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(16, 40))
    labels = int(rng.integers(2, 6))
    image = majority(rng.integers(0, labels, size=(n, n, n)), labels, int(rng.integers(0, 3)))
    spacing = [float(rng.choice([0.5, 1.0, 1.5, 2.0])) for _ in range(3)]
    size = min(spacing) * float(rng.choice([2, 3, 4, 6, 8]))
    options = ["--bcc-size", "%g" % size] + ([] if rng.random() < 0.5 else ["--targets", "centre"])
    return image, spacing, options


with tempfile.TemporaryDirectory() as work:
    for seed in range(IMAGES):
        image, spacing, options = random_case(seed)
        tag = "seed %d (%s voxels, labels %s, spacing %s, %s)" % (
            seed, "x".join(map(str, image.shape)), sorted(np.unique(image).tolist()), spacing, " ".join(options))
        path = os.path.join(work, "random%d.nii" % seed)
        write_nifti(path, image.shape, image.transpose(2, 1, 0).ravel().astype(int).tolist(), dtype="int16",
                    pixdim=(1.0, *spacing))
        out = os.path.join(work, "random%d.vtu" % seed)
        run = subprocess.run([cli, path, "-o", out, "--quiet", "--threads", "2"] + options,
                             capture_output=True, text=True, timeout=600)
        if not check(run.returncode == 0, "%s: cbc3d exits 0 %s" % (tag, run.stderr.strip()[-300:])):
            continue
        points, tets, labels = mt.read_mesh(out)
        report = mt.mesh_report(points, tets, labels)
        for key in sorted(k for k in report if k != "all") + ["all"]:
            r = report[key]
            check(r["hinged"] == 0 and r["nonmanifold_edges"] == 0 and r["nonmanifold_vertices"] == 0,
                  "%s, %s: hinged %d, non-manifold edges %d, vertices %d" % (
                      tag, "whole mesh" if key == "all" else "tissue %d" % key, r["hinged"],
                      r["nonmanifold_edges"], r["nonmanifold_vertices"]))
        angles = dihedral_angles(np.asarray(points, dtype=float)[np.asarray(tets)])
        volumes = signed_volumes(points, tets)
        check(angles.min() >= 20.0 - 1e-6 and angles.max() <= 160.0 + 1e-6 and volumes.min() > 0,
              "%s: %d tets, dihedral angles %.3f to %.3f degrees, smallest volume %.3g" % (
                  tag, len(tets), angles.min(), angles.max(), volumes.min()))
check.finish()
