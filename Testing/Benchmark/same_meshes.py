#!/usr/bin/env python3
"""Meshes the seven shared cases with two builds of the cbc3d command and compares the meshes
byte for byte: the check for changes meant to leave every mesh as it was (moves, splits,
refactoring).

    python3 Testing/Benchmark/same_meshes.py BEFORE/bin/cbc3d AFTER/bin/cbc3d [--format inp]

The cases: the brain at the paper's settings and at defaults, the nidus at the paper's
settings, the ventricles and the 3 mm head (nipype) at defaults, and the k-means head at
defaults and, with the air (label 1) as background, at the paper's settings. Prints one line a
case with both files' SHA-256 and exits 1 when any differ. The files are .vtu by default: the
mesh with every figure of its field data. `--format inp` compares the Abaqus files instead (every
coordinate to the last bit, tets, tissues and surfaces), for changes that add a figure to the
field data but must leave the meshes as they were. Needs ../shared/data; skips
(exit 0, with a message) where it is absent.
"""
import hashlib
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "data"))
PAPER = ["--bcc-size", "8", "--fidelity", "0.95", "--pattern", "edge", "--iterations", "5"]
CASES = [
    ("brain, paper", "cbc3d-brain.nii.gz", PAPER),
    ("brain, defaults", "cbc3d-brain.nii.gz", []),
    ("nidus, paper", "cbc3d-nidus.nii.gz", PAPER),
    ("ventricles, defaults", "cbc3d-ventricles.nii.gz", []),
    ("3 mm head, defaults", "nipype-tissue-labels.nii.gz", []),
    ("k-means, defaults", "itk-t1-kmeans-labels.nii.gz", []),
    ("k-means, background 1, paper", "itk-t1-kmeans-labels.nii.gz", PAPER + ["--background", "1"]),
]


def mesh_digest(cli, image, options, work, extension):
    output = os.path.join(work, "mesh." + extension)
    if os.path.exists(output):
        os.remove(output)
    subprocess.run([cli, os.path.join(SHARED, image), "-o", output, "--threads", "2"] + options,
                   check=True, stdout=subprocess.DEVNULL)
    with open(output, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def main():
    arguments = sys.argv[1:]
    extension = "vtu"
    if len(arguments) == 4 and arguments[2] == "--format" and arguments[3] in ("vtu", "inp"):
        extension = arguments[3]
        arguments = arguments[:2]
    if len(arguments) != 2:
        print(__doc__)
        return 2
    missing = [cli for cli in arguments if not os.access(cli, os.X_OK)]
    if missing:
        print("same_meshes: no cbc3d command at %s" % ", ".join(missing))
        return 2
    if not os.path.isdir(SHARED):
        print("same_meshes: skipped, %s is absent" % SHARED)
        return 0
    differing = 0
    with tempfile.TemporaryDirectory() as work:
        for name, image, options in CASES:
            before = mesh_digest(arguments[0], image, options, work, extension)
            after = mesh_digest(arguments[1], image, options, work, extension)
            same = before == after
            differing += not same
            print("%-30s %s %s %s" % (name, before[:16], after[:16], "same" if same else "DIFFERENT"),
                  flush=True)
    print("all %d cases byte for byte the same" % len(CASES) if not differing
          else "%d of %d cases differ" % (differing, len(CASES)))
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main())
