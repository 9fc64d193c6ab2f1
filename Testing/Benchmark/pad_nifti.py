#!/usr/bin/env python3
"""Pads a NIfTI-1 label image with background (0) on the high side of every axis (plain Python 3).

usage: pad_nifti.py IN.nii[.gz] OUT.nii FACTOR
Each axis grows by FACTOR ** (1/3), rounded up, so that the image holds at least FACTOR times its
voxels. The low side is untouched, so the world frame (origin, spacing, direction) is the same
and a mesh of the padded image can be compared byte for byte with the unpadded one's. The
benchmark's speed targets pad the brain the same way (speed_targets.pad_nifti).
"""
import sys

import benchmark_meshing
import speed_targets


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__.strip().splitlines()[2])
    source, target, factor = sys.argv[1], sys.argv[2], float(sys.argv[3])
    voxels, padded = speed_targets.pad_nifti(benchmark_meshing.read_nifti_header, benchmark_meshing.open_nifti,
                                            source, target, factor)
    print("%s: %d -> %d voxels (%.3f times)" % (target, voxels, padded, padded / voxels))


if __name__ == "__main__":
    main()
