"""Writes the fuzzers' seed corpora: small NIfTI files, valid and broken (corpus/nifti), and
pipeline inputs (corpus/pipeline; the byte layout is FuzzPipeline.cxx's DecodeImage and
DecodeParams). Run with Debian's python3 from the repository root:
    python3 Testing/Fuzz/make_seeds.py
The seeds are committed; files named regression-* in the corpora are inputs that once failed
and are not written here."""
import gzip
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "Python"))
from cbc3d_testing import write_nifti  # noqa: E402

NIFTI = os.path.join(HERE, "corpus", "nifti")
PIPELINE = os.path.join(HERE, "corpus", "pipeline")


def ball(n, radius, label=1):
    c = (n - 1) / 2.0
    return [label if (i % n - c) ** 2 + (i // n % n - c) ** 2 + (i // (n * n) - c) ** 2 <= radius ** 2 else 0
            for i in range(n ** 3)]


def nifti_seeds():
    os.makedirs(NIFTI, exist_ok=True)
    path = lambda name: os.path.join(NIFTI, name)
    values = ball(4, 1.5)
    write_nifti(path("ball-int16.nii"), (4, 4, 4), values)
    write_nifti(path("ball-uint8.nii"), (4, 4, 4), values, "uint8")
    write_nifti(path("ball-float32.nii"), (4, 4, 4), [v * 2.0 for v in values], "float32")
    write_nifti(path("ball-qform.nii"), (4, 4, 4), values, pixdim=(-1.0, 0.5, 0.5, 2.0), qform_code=1,
                quatern=(0.0, 0.0, 1.0), qoffset=(10.0, -5.0, 3.0))
    write_nifti(path("ball-sform.nii"), (4, 4, 4), values, pixdim=(1.0, 2.0, 2.0, 2.0), sform_code=2,
                srows=((-2, 0, 0, 1), (0, 2, 0, 2), (0, 0, 2, 3)))
    write_nifti(path("ball-sheared-sform.nii"), (4, 4, 4), values, sform_code=1,
                srows=((1, 0.5, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0)))
    with open(path("ball-int16.nii"), "rb") as f:
        whole = f.read()
    # mtime 0: the same bytes on every run (gzip.open would stamp the time)
    with open(path("ball.nii.gz"), "wb") as f:
        f.write(gzip.compress(whole, mtime=0))
    with open(path("truncated-header.nii"), "wb") as f:
        f.write(whole[:200])
    with open(path("truncated-data.nii"), "wb") as f:
        f.write(whole[:352 + 40])
    with open(path("truncated.nii.gz"), "wb") as f:
        f.write(gzip.compress(whole, mtime=0)[:60])
    # A header that claims a far larger image than the file holds.
    huge = bytearray(whole)
    struct.pack_into("<8h", huge, 40, 3, 30000, 30000, 30000, 1, 1, 1, 1)
    with open(path("huge-dims.nii"), "wb") as f:
        f.write(bytes(huge))


def pipeline_seed(name, dims, spacing_steps, direction, labels, voxels, edge_step=5, fidelity=3,
                  iterations=2, pattern=1, background_extra=1):
    """One input for FuzzPipeline.cxx: dims 2..12, spacing 0.25 mm steps (1..16), direction
    choice (0..2), origin bytes, a background choice, the label count, then the voxels (indices
    into the fuzzer's label table), then the stage parameters."""
    header = [d - 2 for d in dims] + [s - 1 for s in spacing_steps] + [direction, 128, 128, 128]
    header += [background_extra, labels - 2]
    params = [edge_step, fidelity, 1, 1, iterations, pattern, 1, 1]
    with open(os.path.join(PIPELINE, name), "wb") as f:
        f.write(bytes(header + voxels + params))


def pipeline_seeds():
    os.makedirs(PIPELINE, exist_ok=True)
    pipeline_seed("ball-8.bin", (8, 8, 8), (4, 4, 4), 0, 2, ball(8, 3.0))
    pipeline_seed("two-balls-reflected.bin", (8, 8, 8), (4, 4, 8), 1, 3,
                  [max(a, 2 * b) for a, b in zip(ball(8, 3.5), ball(8, 1.8))], iterations=3)
    pipeline_seed("permuted-anisotropic.bin", (6, 6, 6), (2, 5, 9), 2, 3,
                  [(i * 7 // 5) % 3 for i in range(216)], fidelity=4)
    pipeline_seed("thin-sheet.bin", (10, 10, 4), (4, 4, 4), 0, 2,
                  [1 if i // 100 == 1 else 0 for i in range(400)], edge_step=0)
    pipeline_seed("checkerboard.bin", (5, 5, 5), (4, 4, 4), 0, 5,
                  [(i % 5 + i // 5 % 5 + i // 25) % 4 for i in range(125)], iterations=1)
    pipeline_seed("lattice-only.bin", (12, 12, 12), (4, 4, 4), 0, 2, ball(12, 5.0), fidelity=0,
                  iterations=0)


if __name__ == "__main__":
    nifti_seeds()
    pipeline_seeds()
