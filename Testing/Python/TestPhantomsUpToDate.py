"""Check that the phantoms committed in Data/ are what Data/GeneratePhantoms.py writes, and
that they have the properties they are documented to have (Data/README.md).

Run as:  CBC3D_SOURCE_DIR=/path/to/source pvpython Testing/Python/TestPhantomsUpToDate.py
(CBC3D_SOURCE_DIR defaults to this script's folder ../..). Exits 0 on success, 1 with a
message per failure otherwise.
"""

import gzip
import itertools
import math
import os
import runpy
import shutil
import struct
import sys
import tempfile

import numpy as np

from vtkmodules.util import numpy_support
from vtkmodules.vtkIOImage import vtkNIFTIImageReader
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

SOURCE_DIR = os.environ.get("CBC3D_SOURCE_DIR") or os.path.normpath(
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
DATA_DIR = os.path.join(SOURCE_DIR, "Data")
GENERATOR = os.path.join(DATA_DIR, "GeneratePhantoms.py")
VTI_FILES = ("ball.vti", "nested_shells.vti", "touching_boxes.vti", "thin_tube.vti",
             "oblique_ball.vti")
NIFTI_FILES = ("shells.nii.gz",)
MAX_BYTES = 100 * 1024

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks  # noqa: E402

check = Checks()
failures = check.failures


def read_vti(path):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    if image is None or image.GetNumberOfPoints() == 0:
        raise RuntimeError("cannot read " + path)
    return image


def direction(image):
    m = image.GetDirectionMatrix()
    return [[m.GetElement(r, c) for c in range(3)] for r in range(3)]


def labels(image):
    array = image.GetPointData().GetArray("Labels")
    return array, numpy_support.vtk_to_numpy(array)


def label_at(values, dims, i, j, k):
    return int(values[i + dims[0] * (j + dims[1] * k)])


def det3(m):
    return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))


def compare_vti(name, committed_path, fresh_path):
    a, b = read_vti(committed_path), read_vti(fresh_path)
    check(a.GetDimensions() == b.GetDimensions(), "%s: dimensions %s != regenerated %s"
          % (name, a.GetDimensions(), b.GetDimensions()))
    check(a.GetOrigin() == b.GetOrigin(), "%s: origin %s != regenerated %s"
          % (name, a.GetOrigin(), b.GetOrigin()))
    check(a.GetSpacing() == b.GetSpacing(), "%s: spacing %s != regenerated %s"
          % (name, a.GetSpacing(), b.GetSpacing()))
    check(direction(a) == direction(b), "%s: direction %s != regenerated %s"
          % (name, direction(a), direction(b)))
    check(a.GetPointData().GetNumberOfArrays() == 1 and b.GetPointData().GetNumberOfArrays() == 1,
          "%s: expected exactly one point array" % name)
    arr_a, val_a = labels(a)
    arr_b, val_b = labels(b)
    if not check(arr_a is not None and arr_b is not None, "%s: no point array 'Labels'" % name):
        return
    check(arr_a.GetDataType() == arr_b.GetDataType(), "%s: type %s != regenerated %s"
          % (name, arr_a.GetDataTypeAsString(), arr_b.GetDataTypeAsString()))
    check(arr_a.GetNumberOfComponents() == 1, "%s: Labels has %d components"
          % (name, arr_a.GetNumberOfComponents()))
    check(val_a.shape == val_b.shape and np.array_equal(val_a, val_b),
          "%s: label values differ from the regenerated ones" % name)
    with open(committed_path, "rb") as f:
        head = f.read(4096)
    check(b'format="appended"' not in head and b'format="binary"' in head
          and b"vtkZLibDataCompressor" in head,
          "%s: not written in binary mode with zlib compression" % name)


def check_ball(image):
    dims, spacing, origin = image.GetDimensions(), image.GetSpacing(), image.GetOrigin()
    check(dims == (32, 32, 32) and spacing == (1.0, 1.0, 1.0), "ball: expected 32^3 at 1 mm")
    check(origin != (0.0, 0.0, 0.0), "ball: origin should be non-zero")
    _, values = labels(image)
    # Count the integer grid points within 10 (index units = mm) of the grid centre 15.5.
    expected = 0
    wrong = 0
    for k, j, i in itertools.product(range(32), repeat=3):
        inside = (i - 15.5) ** 2 + (j - 15.5) ** 2 + (k - 15.5) ** 2 <= 100.0
        expected += inside
        wrong += (label_at(values, dims, i, j, k) == 1) != inside
    check(int(np.count_nonzero(values == 1)) == expected,
          "ball: %d voxels of label 1, expected %d" % (np.count_nonzero(values == 1), expected))
    check(wrong == 0, "ball: %d voxels have the wrong label" % wrong)
    check(set(np.unique(values).tolist()) == {0, 1}, "ball: labels are not {0, 1}")


def check_shells(image):
    _, values = labels(image)
    found = set(np.unique(values).tolist())
    check(found == {0, 1, 2, 3}, "nested_shells: labels %s, expected {0, 1, 2, 3}" % found)


def check_boxes(image):
    dims, spacing = image.GetDimensions(), image.GetSpacing()
    check(len(set(spacing)) > 1, "touching_boxes: spacing %s is not anisotropic" % (spacing,))
    _, values = labels(image)
    v = values.reshape(dims[2], dims[1], dims[0])
    check(set(np.unique(v).tolist()) == {0, 1, 2}, "touching_boxes: labels are not {0, 1, 2}")
    touching = 0
    for axis in range(3):
        lo = [slice(None)] * 3
        hi = [slice(None)] * 3
        lo[axis] = slice(0, -1)
        hi[axis] = slice(1, None)
        a, b = v[tuple(lo)], v[tuple(hi)]
        touching += int(np.count_nonzero((a == 1) & (b == 2)) + np.count_nonzero((a == 2) & (b == 1)))
    check(touching > 0, "touching_boxes: no voxel of label 1 is a face-neighbour of label 2")


def check_tube(image):
    _, values = labels(image)
    found = set(np.unique(values).tolist())
    check(found == {0, 1, 2}, "thin_tube: labels %s, expected {0, 1, 2}" % found)
    dims = image.GetDimensions()
    v = values.reshape(dims[2], dims[1], dims[0])
    plate_slices = [k for k in range(dims[2]) if np.any(v[k] == 2)]
    check(len(plate_slices) == 1, "thin_tube: the plate spans slices %s, expected one" % plate_slices)


def check_oblique(image):
    array, values = labels(image)
    check(array.GetDataTypeAsString() == "unsigned short",
          "oblique_ball: type %s, expected uint16" % array.GetDataTypeAsString())
    found = set(np.unique(values).tolist())
    check(found == {0, 128}, "oblique_ball: labels %s, expected {0, 128}" % found)
    d = direction(image)
    check(abs(det3(d) + 1.0) < 1e-9, "oblique_ball: direction determinant %r, expected -1" % det3(d))
    check(image.GetOrigin() != (0.0, 0.0, 0.0), "oblique_ball: origin should be non-zero")
    check(len(set(image.GetSpacing())) == 3, "oblique_ball: spacing should be anisotropic")
    # A ball of radius 8 mm in WORLD space (VTK's own index -> physical transform), centred
    # at the grid centre.
    dims = image.GetDimensions()
    centre = [0.0, 0.0, 0.0]
    image.TransformContinuousIndexToPhysicalPoint([(n - 1) / 2.0 for n in dims], centre)
    wrong = 0
    p = [0.0, 0.0, 0.0]
    for k, j, i in itertools.product(range(dims[2]), range(dims[1]), range(dims[0])):
        image.TransformIndexToPhysicalPoint(i, j, k, p)
        inside = math.dist(p, centre) <= 8.0
        wrong += (label_at(values, dims, i, j, k) == 128) != inside
    check(wrong == 0, "oblique_ball: %d voxels disagree with a world-space ball of radius 8" % wrong)


def check_nifti(path, shells_image):
    with gzip.open(path, "rb") as f:
        raw = f.read()
    check(struct.unpack_from("<i", raw, 0)[0] == 348 and raw[344:348] == b"n+1\x00",
          "shells.nii.gz: not a single-file NIfTI-1")
    check(struct.unpack_from("<h", raw, 70)[0] == 16, "shells.nii.gz: datatype is not float32")
    qform_code, sform_code = struct.unpack_from("<hh", raw, 252)
    check(sform_code == 1, "shells.nii.gz: sform_code %d, expected 1" % sform_code)
    reader = vtkNIFTIImageReader()
    reader.SetFileName(path)
    reader.Update()
    sform = reader.GetSFormMatrix()
    if check(sform is not None, "shells.nii.gz: vtkNIFTIImageReader finds no sform"):
        m = [[sform.GetElement(r, c) for c in range(3)] for r in range(3)]
        check(abs(det3(m) - 1.0) < 1e-5, "shells.nii.gz: sform rotation determinant %r" % det3(m))
        check(any(abs(m[r][c]) > 1e-3 for r in range(3) for c in range(3) if r != c),
              "shells.nii.gz: sform has no rotation")
        check(any(abs(sform.GetElement(r, 3)) > 0 for r in range(3)),
              "shells.nii.gz: sform has no translation")
    values = numpy_support.vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
    _, shells = labels(shells_image)
    check(reader.GetOutput().GetDimensions() == shells_image.GetDimensions()
          and np.array_equal(values, shells.astype(np.float32)),
          "shells.nii.gz: voxels differ from nested_shells.vti")


def main():
    if not os.path.isfile(GENERATOR):
        print("FAIL: %s not found (set CBC3D_SOURCE_DIR)" % GENERATOR)
        return 1
    tmp = tempfile.mkdtemp(prefix="cbc3d-phantoms-")
    try:
        saved_argv = sys.argv
        sys.argv = [GENERATOR, tmp]
        try:
            runpy.run_path(GENERATOR, run_name="__main__")
            code = 0
        except SystemExit as e:
            code = e.code
        finally:
            sys.argv = saved_argv
        if not check(code in (0, None), "GeneratePhantoms.py exited with %r" % code):
            return 1

        for name in VTI_FILES + NIFTI_FILES:
            committed = os.path.join(DATA_DIR, name)
            fresh = os.path.join(tmp, name)
            if not check(os.path.isfile(committed), "Data/%s is missing: run "
                         "'pvpython Data/GeneratePhantoms.py'" % name):
                continue
            if not check(os.path.isfile(fresh), "the generator did not write %s" % name):
                continue
            size = os.path.getsize(committed)
            check(size < MAX_BYTES, "Data/%s is %d bytes, over %d" % (name, size, MAX_BYTES))
            before = len(failures)
            if name.endswith(".vti"):
                compare_vti(name, committed, fresh)
            else:
                with gzip.open(committed, "rb") as a, gzip.open(fresh, "rb") as b:
                    check(a.read() == b.read(), "%s: decompressed bytes differ" % name)
            if len(failures) > before:
                print("  -> Data/%s is out of date: regenerate it with "
                      "'pvpython Data/GeneratePhantoms.py'" % name)

        present = lambda n: os.path.isfile(os.path.join(DATA_DIR, n))
        if present("ball.vti"):
            check_ball(read_vti(os.path.join(DATA_DIR, "ball.vti")))
        if present("nested_shells.vti"):
            shells = read_vti(os.path.join(DATA_DIR, "nested_shells.vti"))
            check_shells(shells)
            if present("shells.nii.gz"):
                check_nifti(os.path.join(DATA_DIR, "shells.nii.gz"), shells)
        if present("touching_boxes.vti"):
            check_boxes(read_vti(os.path.join(DATA_DIR, "touching_boxes.vti")))
        if present("thin_tube.vti"):
            check_tube(read_vti(os.path.join(DATA_DIR, "thin_tube.vti")))
        if present("oblique_ball.vti"):
            check_oblique(read_vti(os.path.join(DATA_DIR, "oblique_ball.vti")))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    print("all phantoms up to date and as documented")
    return 0


if __name__ == "__main__":
    try:
        status = main()
    except Exception:  # a corrupt or unreadable file: report it as a failure, not a crash
        import traceback
        traceback.print_exc()
        print("FAIL: unexpected error while checking the phantoms (corrupt file in Data/?)")
        status = 1
    sys.exit(status)
