"""pvpython test of the CBC3D NIfTI reader proxy (ParaViewPlugin/CBC3DReaders.xml).

Checks that, once the plugin is loaded, OpenDataFile picks CBC3DNIfTIReader for .nii and
.nii.gz files, and that ParaView's data information places the image in its NIfTI world frame:
the bounds must be those of the voxel centres that the NIfTI-1 standard's formulas give, computed
here from the raw header with gzip + struct only.

1. Synthetic images written by this script (no data needed): an oblique sform with a reflection
   (.nii.gz) and a rotated qform with qfac = -1 (.nii).
2. Real images from $CBC3D_SHARED_DATA: cbc3d-ventricles.nii.gz (240 x 240 x 134, spacing 1,
   label 128) and cbc3d-brain.nii.gz (286 x 286 x 90, anisotropic). Skipped (exit 77, after
   part 1) when that folder is absent.

Environment: CBC3D_PLUGIN (the plugin .so), CBC3D_SHARED_DATA, CBC3D_TEST_OUTPUT (folder for the
synthetic files; default: a temporary folder). Exits 0 on success, 1 on failure, 77 to skip.
"""

import itertools
import math
import os
import sys
import tempfile

import numpy as np

from paraview import servermanager
from paraview.simple import LoadPlugin, OpenDataFile, Delete
from vtkmodules.util import numpy_support

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks, read_nifti_header as read_header, write_nifti  # noqa: E402

check = Checks()
failures = check.failures


def write_numbered(path, dims, pixdim, **transforms):
    """An int16 image whose voxel at file index (i, j, k) holds 1 + i + nx*(j + ny*k)."""
    write_nifti(path, dims, range(1, dims[0] * dims[1] * dims[2] + 1), "int16", pixdim, **transforms)


def world(h, i, j, k):
    """World (RAS mm) position of file voxel (i, j, k): sform > qform > voxel size."""
    if h["sform_code"] > 0:
        return [r[0] * i + r[1] * j + r[2] * k + r[3] for r in h["srow"]]
    p = (h["pixdim"][1] * i, h["pixdim"][2] * j, h["pixdim"][3] * k)
    if h["qform_code"] > 0:
        b, c, d = h["quatern"]
        a = math.sqrt(max(0.0, 1.0 - (b * b + c * c + d * d)))
        qfac = -1.0 if h["pixdim"][0] < 0 else 1.0
        R = ((a * a + b * b - c * c - d * d, 2 * b * c - 2 * a * d, 2 * b * d + 2 * a * c),
             (2 * b * c + 2 * a * d, a * a + c * c - b * b - d * d, 2 * c * d - 2 * a * b),
             (2 * b * d - 2 * a * c, 2 * c * d + 2 * a * b, a * a + d * d - c * c - b * b))
        q = (p[0], p[1], qfac * p[2])
        return [sum(R[r][m] * q[m] for m in range(3)) + h["qoffset"][r] for r in range(3)]
    return list(p)


def corners(h):
    n = h["dim"][1:4]
    return [world(h, i, j, k)
            for i, j, k in itertools.product((0, n[0] - 1), (0, n[1] - 1), (0, n[2] - 1))]


def expected_bounds(h):
    pts = corners(h)
    return [f(p[a] for p in pts) for a in range(3) for f in (min, max)]


# ---------------------------------------------------------------------------------------------

def check_reader(path, name, frame, dims=None, spacing=None, label=None, det=None):
    """Open `path` with OpenDataFile and compare it with its own header."""
    h = read_header(path)
    try:
        reader = OpenDataFile(path)
    except RuntimeError as error:
        check(False, "%s: OpenDataFile failed: %s" % (name, error))
        return
    if not check(reader is not None, name + ": OpenDataFile found a reader"):
        return
    check(reader.GetXMLName() == "CBC3DNIfTIReader",
          "%s: proxy is CBC3DNIfTIReader, got %s" % (name, reader.GetXMLName()))
    check(reader.GetVTKClassName() == "vtkCBC3DNIfTIReader",
          "%s: class is vtkCBC3DNIfTIReader, got %s" % (name, reader.GetVTKClassName()))
    reader.UpdatePipeline()
    reader.UpdatePipelineInformation()
    check(reader.GetPropertyValue("FrameSource") == frame,
          "%s: frame source %s, got %s" % (name, frame, reader.GetPropertyValue("FrameSource")))

    info = reader.GetDataInformation()
    n = h["dim"][1:4]
    extent = info.GetExtent()
    check(tuple(extent) == (0, n[0] - 1, 0, n[1] - 1, 0, n[2] - 1),
          "%s: extent %s matches dim %s" % (name, extent, n))
    bounds = info.GetBounds()
    want = expected_bounds(h)
    gap = max(abs(x - y) for x, y in zip(bounds, want))
    check(gap < 1e-6, "%s: ParaView bounds %s, header corners give %s" % (name, bounds, want))

    image = servermanager.Fetch(reader)
    got_dims = image.GetDimensions()
    if dims is not None:
        check(tuple(got_dims) == tuple(dims), "%s: dimensions %s, want %s" % (name, got_dims, dims))
    got_spacing = image.GetSpacing()
    want_spacing = spacing if spacing is not None else [abs(s) for s in h["pixdim"][1:4]]
    check(max(abs(x - y) for x, y in zip(got_spacing, want_spacing)) < 1e-6,
          "%s: spacing %s, want %s" % (name, got_spacing, want_spacing))

    # Each corner voxel of the file, found in the output by value where values are distinct
    # (synthetic files), else as the set of the 8 corner positions (real files).
    got = []
    for I, J, K in itertools.product((0, got_dims[0] - 1), (0, got_dims[1] - 1),
                                     (0, got_dims[2] - 1)):
        p = [0.0, 0.0, 0.0]
        image.TransformIndexToPhysicalPoint(I, J, K, p)
        got.append(p)
    want_pts = corners(h)
    worst = max(min(math.dist(p, q) for q in got) for p in want_pts)
    check(worst < 1e-6, "%s: corner voxels at their header positions (worst %.3g mm)"
          % (name, worst))

    values = numpy_support.vtk_to_numpy(image.GetPointData().GetScalars())
    if label is not None:
        check(label in np.unique(values), "%s: label %d present" % (name, label))
    got_det = np.linalg.det(np.array([[image.GetDirectionMatrix().GetElement(r, c)
                                       for c in range(3)] for r in range(3)]))
    if det is not None:
        check(abs(got_det - det) < 1e-5, "%s: det(direction) %g, want %g" % (name, got_det, det))
    print("%s: %s, frame %s, dims %s, spacing %s, bounds %s, det(direction) %+.3f"
          % (name, reader.GetXMLName(), reader.GetPropertyValue("FrameSource"), got_dims,
             tuple(round(s, 6) for s in got_spacing), tuple(round(b, 4) for b in bounds), got_det))
    Delete(reader)
    return image


def main():
    plugin = os.environ.get("CBC3D_PLUGIN")
    if not plugin or not os.path.exists(plugin):
        print("FAIL: CBC3D_PLUGIN does not name the plugin .so: %r" % plugin)
        return 1
    LoadPlugin(plugin, remote=False, ns=globals())

    out = os.environ.get("CBC3D_TEST_OUTPUT") or tempfile.mkdtemp()
    out = os.path.join(out, "TestNIfTIReaderPlugin")
    os.makedirs(out, exist_ok=True)

    # 1a. sform: rotation of 25 degrees about z, then x reflected (det -1), anisotropic voxels,
    # gzip-compressed. No qform, so VTK reverses the slices; positions must not change.
    spacing = (0.7, 1.3, 2.1)
    cz, sz = math.cos(math.radians(25)), math.sin(math.radians(25))
    rot = ((-cz, -sz, 0.0), (-sz, cz, 0.0), (0.0, 0.0, 1.0))  # Rz(25) with column x negated
    t = (31.5, -12.0, 48.25)
    srows = tuple(tuple(rot[r][c] * spacing[c] for c in range(3)) + (t[r],) for r in range(3))
    path_a = os.path.join(out, "oblique_reflected.nii.gz")
    write_numbered(path_a, (6, 4, 5), (1.0,) + spacing, sform_code=1, srows=srows)
    check_reader(path_a, "oblique reflected sform (.nii.gz)", "sform", dims=(6, 4, 5))

    # 1b. the same sform beside an identity qform (qfac = +1): VTK keeps the slice order, so the
    # reflection reaches ParaView as a direction matrix with determinant -1.
    path_c = os.path.join(out, "oblique_reflected_with_qform.nii")
    write_numbered(path_c, (6, 4, 5), (1.0,) + spacing, qform_code=1, sform_code=1, srows=srows)
    check_reader(path_c, "oblique reflected sform + qform (.nii)", "sform", dims=(6, 4, 5),
                 det=-1.0)

    # 1c. qform only, qfac = -1, rotated; the srows are garbage that must be ignored.
    path_b = os.path.join(out, "qform_qfac_neg.nii")
    write_numbered(path_b, (5, 3, 4), (-1.0, 1.1, 0.9, 1.6), qform_code=1,
                quatern=(0.2, -0.1, 0.4), qoffset=(-5.0, 17.0, 2.5),
                srows=((9, 9, 9, 9), (0, 0, 0, 0), (0, 0, 0, 0)))
    check_reader(path_b, "qform qfac=-1 (.nii)", "qform", dims=(5, 3, 4))

    # 2. Real images.
    shared = os.environ.get("CBC3D_SHARED_DATA", "")
    if not shared or not os.path.isdir(shared):
        print("SKIP: real-image checks need CBC3D_SHARED_DATA (a folder with cbc3d-*.nii.gz); "
              "%r does not exist" % shared)
        return 1 if failures else 77
    ventricles = os.path.join(shared, "cbc3d-ventricles.nii.gz")
    brain = os.path.join(shared, "cbc3d-brain.nii.gz")
    for path in (ventricles, brain):
        check(os.path.exists(path), "missing " + path)
    if os.path.exists(ventricles):
        check_reader(ventricles, "cbc3d-ventricles", "sform", dims=(240, 240, 134),
                     spacing=(1.0, 1.0, 1.0), label=128)
    if os.path.exists(brain):
        check_reader(brain, "cbc3d-brain", "sform", dims=(286, 286, 90),
                     spacing=(0.859375, 0.859375, 2.5), label=1)
    return 1 if failures else 0


if __name__ == "__main__":
    status = main()
    print("%d failure(s)" % len(failures) if failures else "all checks passed")
    sys.exit(status)
