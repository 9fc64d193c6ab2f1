#!/usr/bin/env pvpython
"""Write the small synthetic label images ("phantoms") of Data/.

Usage:  pvpython Data/GeneratePhantoms.py [OUTPUT_DIR]      (default: this script's folder)

Uses only the Python standard library, numpy and the VTK bundled with pvpython. The output
is deterministic (no timestamps, fixed ordering): running it twice gives the same files.
Every image is a 3-D vtkImageData with one one-component point array "Labels"
(label 0 = background), written by vtkXMLImageDataWriter in *binary* (not appended) mode with
zlib compression: with Debian 12's libexpat, VTK 9.2 cannot read back appended files over
about 4 KB. See Data/README.md for what each phantom is.

Voxel membership is always decided at the voxel centre's WORLD position
    world = origin + direction * (spacing .* ijk),
so a ball is a ball in world space even for anisotropic spacing and oblique directions.
"""

import gzip
import io
import os
import struct
import sys

import numpy as np

from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

# --------------------------------------------------------------------------------------------
# Phantom definitions (the single source of truth; Data/README.md and the test repeat them).
# --------------------------------------------------------------------------------------------

# 1. ball.vti: label 1, radius 10 mm, centred in a 32^3 grid of 1 mm spacing.
BALL = dict(dims=(32, 32, 32), spacing=(1.0, 1.0, 1.0), origin=(-20.0, 10.5, 5.25),
            radius=10.0, label=1)

# 2. nested_shells.vti (and shells.nii.gz): ball 3 (r <= 5), shell 2 (5 < r <= 9),
#    shell 1 (9 < r <= 13), centred in a 32^3 grid of 1 mm spacing.
SHELLS = dict(dims=(32, 32, 32), spacing=(1.0, 1.0, 1.0), origin=(-15.5, -15.5, -15.5),
              radii=((5.0, 3), (9.0, 2), (13.0, 1)))

# 3. touching_boxes.vti: two boxes (inclusive index ranges) sharing part of the face between
#    i = 11 and i = 12, anisotropic spacing 1 x 1 x 2 mm.
BOXES = dict(dims=(24, 20, 12), spacing=(1.0, 1.0, 2.0), origin=(0.5, -3.0, 7.0),
             boxes=(((4, 11), (3, 16), (2, 9), 1),
                    ((12, 19), (6, 13), (3, 8), 2)))

# 4. thin_tube.vti: a capsule of radius 1.5 mm around a diagonal segment (label 1) and a
#    plate one voxel thick at k = 15 (label 2). Segment ends are given in index coordinates
#    (spacing is 1 mm, direction identity, so index offsets are millimetres).
TUBE = dict(dims=(32, 32, 20), spacing=(1.0, 1.0, 1.0), origin=(2.0, -3.0, 1.5),
            tube=((4.0, 4.0, 4.0), (27.0, 26.0, 9.0), 1.5, 1),
            plate=((6, 25), (4, 27), (15, 15), 2))

# 5. oblique_ball.vti: uint16 label 128, radius 8 mm ball centred in the grid, anisotropic
#    spacing, non-zero origin, and a direction matrix that is a rotation combined with a
#    reflection (det = -1). Rz(a) * Rx(b) * diag(1, 1, -1) with cos a = 0.6, sin a = 0.8,
#    cos b = 0.28, sin b = 0.96: every entry is a short decimal, so it prints and parses back
#    exactly.
OBLIQUE_DIRECTION = ((0.6, -0.224, -0.768),
                     (0.8, 0.168, 0.576),
                     (0.0, 0.96, -0.28))
OBLIQUE = dict(dims=(28, 22, 16), spacing=(0.8, 1.0, 1.5), origin=(30.0, -12.5, 101.25),
               direction=OBLIQUE_DIRECTION, radius=8.0, label=128)

# 6. shells.nii.gz: the nested_shells voxels as float32 NIfTI-1 with an sform (sform_code 1,
#    qform_code 0) = proper rotation Rz(a) * Rx(b) (as above, without the reflection) times
#    the 1 mm spacing, plus a translation.
NIFTI_ROTATION = ((0.6, -0.224, 0.768),
                  (0.8, 0.168, -0.576),
                  (0.0, 0.96, 0.28))
NIFTI_TRANSLATION = (-40.0, 25.5, -10.25)


# --------------------------------------------------------------------------------------------
# Helpers
# --------------------------------------------------------------------------------------------

def world_coordinates(dims, spacing, origin, direction=None):
    """World x, y, z of every voxel centre as arrays of shape (nz, ny, nx)."""
    k, j, i = np.meshgrid(np.arange(dims[2], dtype=np.float64),
                          np.arange(dims[1], dtype=np.float64),
                          np.arange(dims[0], dtype=np.float64), indexing="ij")
    p = (i * spacing[0], j * spacing[1], k * spacing[2])
    if direction is None:
        direction = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    return tuple(origin[r] + direction[r][0] * p[0] + direction[r][1] * p[1]
                 + direction[r][2] * p[2] for r in range(3))


def grid_centre_world(dims, spacing, origin, direction=None):
    """World position of the centre of the grid (index (n - 1) / 2 along each axis)."""
    c = [(dims[a] - 1) / 2.0 * spacing[a] for a in range(3)]
    if direction is None:
        return tuple(origin[r] + c[r] for r in range(3))
    return tuple(origin[r] + sum(direction[r][a] * c[a] for a in range(3)) for r in range(3))


def make_image(labels, spacing, origin, direction=None):
    """vtkImageData holding labels (numpy array of shape (nz, ny, nx)) as point array Labels."""
    nz, ny, nx = labels.shape
    image = vtkImageData()
    image.SetDimensions(nx, ny, nz)
    image.SetSpacing(*spacing)
    image.SetOrigin(*origin)
    if direction is not None:
        image.SetDirectionMatrix([float(direction[r][c]) for r in range(3) for c in range(3)])
    array = numpy_support.numpy_to_vtk(np.ascontiguousarray(labels).ravel(order="C"), deep=1)
    array.SetName("Labels")
    image.GetPointData().SetScalars(array)
    return image


def write_vti(image, path):
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.SetDataModeToBinary()  # never appended: see the module docstring
    writer.SetCompressorTypeToZLib()
    writer.SetCompressionLevel(9)
    if writer.Write() != 1:
        raise RuntimeError("vtkXMLImageDataWriter failed to write " + path)


# --------------------------------------------------------------------------------------------
# Phantoms
# --------------------------------------------------------------------------------------------

def ball_labels(p=BALL):
    x, y, z = world_coordinates(p["dims"], p["spacing"], p["origin"])
    c = grid_centre_world(p["dims"], p["spacing"], p["origin"])
    d2 = (x - c[0]) ** 2 + (y - c[1]) ** 2 + (z - c[2]) ** 2
    labels = np.zeros(d2.shape, dtype=np.uint8)
    labels[d2 <= p["radius"] ** 2] = p["label"]
    return labels


def shells_labels(p=SHELLS):
    x, y, z = world_coordinates(p["dims"], p["spacing"], p["origin"])
    c = grid_centre_world(p["dims"], p["spacing"], p["origin"])
    d2 = (x - c[0]) ** 2 + (y - c[1]) ** 2 + (z - c[2]) ** 2
    labels = np.zeros(d2.shape, dtype=np.uint8)
    # Paint from the outside in, so that each label keeps (r_inner, r_outer].
    for radius, label in sorted(p["radii"], reverse=True):
        labels[d2 <= radius ** 2] = label
    return labels


def boxes_labels(p=BOXES):
    nx, ny, nz = p["dims"]
    labels = np.zeros((nz, ny, nx), dtype=np.uint8)
    for (i0, i1), (j0, j1), (k0, k1), label in p["boxes"]:
        labels[k0:k1 + 1, j0:j1 + 1, i0:i1 + 1] = label
    return labels


def tube_labels(p=TUBE):
    nx, ny, nz = p["dims"]
    k, j, i = np.meshgrid(np.arange(nz, dtype=np.float64), np.arange(ny, dtype=np.float64),
                          np.arange(nx, dtype=np.float64), indexing="ij")
    labels = np.zeros((nz, ny, nx), dtype=np.uint8)
    (a, b, radius, label) = p["tube"]
    s = p["spacing"]
    # Millimetre offsets from the segment start (direction is the identity).
    q = ((i - a[0]) * s[0], (j - a[1]) * s[1], (k - a[2]) * s[2])
    ab = tuple((b[r] - a[r]) * s[r] for r in range(3))
    ab2 = sum(v * v for v in ab)
    t = np.clip((q[0] * ab[0] + q[1] * ab[1] + q[2] * ab[2]) / ab2, 0.0, 1.0)
    d2 = sum((q[r] - t * ab[r]) ** 2 for r in range(3))
    labels[d2 <= radius ** 2] = label
    (i0, i1), (j0, j1), (k0, k1), plate = p["plate"]
    labels[k0:k1 + 1, j0:j1 + 1, i0:i1 + 1] = plate
    return labels


def oblique_labels(p=OBLIQUE):
    x, y, z = world_coordinates(p["dims"], p["spacing"], p["origin"], p["direction"])
    c = grid_centre_world(p["dims"], p["spacing"], p["origin"], p["direction"])
    d2 = (x - c[0]) ** 2 + (y - c[1]) ** 2 + (z - c[2]) ** 2
    labels = np.zeros(d2.shape, dtype=np.uint16)
    labels[d2 <= p["radius"] ** 2] = p["label"]
    return labels


def nifti_bytes(labels, spacing, rotation, translation):
    """NIfTI-1 single file (n+1) image: 348-byte header, 4 zero extension bytes, float32 data.

    sform_code 1 (scanner anatomical) with srow = rotation * diag(spacing) | translation;
    qform_code 0 (no qform), so the sform is the only frame of the file.
    """
    nz, ny, nx = labels.shape
    header = bytearray(348)
    struct.pack_into("<i", header, 0, 348)                          # sizeof_hdr
    struct.pack_into("<B", header, 38, ord("r"))                    # regular (legacy field)
    struct.pack_into("<8h", header, 40, 3, nx, ny, nz, 1, 1, 1, 1)  # dim
    struct.pack_into("<hhh", header, 70, 16, 32, 0)                 # datatype FLOAT32, bitpix
    struct.pack_into("<8f", header, 76, 1.0, spacing[0], spacing[1], spacing[2],
                     0.0, 0.0, 0.0, 0.0)                            # pixdim (qfac = 1)
    struct.pack_into("<fff", header, 108, 352.0, 1.0, 0.0)          # vox_offset, scl_slope/inter
    struct.pack_into("<ff", header, 124, 3.0, 0.0)                  # cal_max, cal_min
    struct.pack_into("<B", header, 123, 2)                          # xyzt_units: mm
    description = b"cbc3d nested shells phantom (Data/GeneratePhantoms.py)"
    header[148:148 + len(description)] = description                # descrip (80 bytes)
    struct.pack_into("<hh", header, 252, 0, 1)                      # qform_code, sform_code
    for r in range(3):
        row = [rotation[r][c] * spacing[c] for c in range(3)] + [translation[r]]
        struct.pack_into("<4f", header, 280 + 16 * r, *row)          # srow_x, srow_y, srow_z
    header[344:348] = b"n+1\x00"                                    # magic
    data = np.ascontiguousarray(labels, dtype="<f4").tobytes(order="C")
    return bytes(header) + b"\x00\x00\x00\x00" + data


def write_nifti_gz(raw, path):
    buffer = io.BytesIO()
    # mtime=0 and no file name in the gzip header: same bytes on every run.
    with gzip.GzipFile(filename="", mode="wb", compresslevel=9, fileobj=buffer, mtime=0) as f:
        f.write(raw)
    with open(path, "wb") as f:
        f.write(buffer.getvalue())


PHANTOMS = ("ball.vti", "nested_shells.vti", "touching_boxes.vti", "thin_tube.vti",
            "oblique_ball.vti", "shells.nii.gz")


def generate(output_dir):
    """Write every phantom into output_dir; return the list of paths written, in order."""
    os.makedirs(output_dir, exist_ok=True)
    paths = [os.path.join(output_dir, name) for name in PHANTOMS]
    write_vti(make_image(ball_labels(), BALL["spacing"], BALL["origin"]), paths[0])
    shells = shells_labels()
    write_vti(make_image(shells, SHELLS["spacing"], SHELLS["origin"]), paths[1])
    write_vti(make_image(boxes_labels(), BOXES["spacing"], BOXES["origin"]), paths[2])
    write_vti(make_image(tube_labels(), TUBE["spacing"], TUBE["origin"]), paths[3])
    write_vti(make_image(oblique_labels(), OBLIQUE["spacing"], OBLIQUE["origin"],
                         OBLIQUE["direction"]), paths[4])
    write_nifti_gz(nifti_bytes(shells, SHELLS["spacing"], NIFTI_ROTATION, NIFTI_TRANSLATION),
                   paths[5])
    return paths


def main(argv):
    if len(argv) > 2 or (len(argv) == 2 and argv[1] in ("-h", "--help")):
        print(__doc__)
        return 0 if len(argv) == 2 else 2
    output_dir = argv[1] if len(argv) == 2 else os.path.dirname(os.path.abspath(__file__))
    for path in generate(output_dir):
        print("wrote %s (%d bytes)" % (path, os.path.getsize(path)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
