"""Helpers shared by the Python tests (pvpython and plain Python): checks that collect
failures, dihedral angles computed with numpy apart from the C++ code, and NIfTI-1 files
written and read with the standard library (offsets from the NIfTI-1 standard, nifti1.h)."""
import gzip
import struct
import sys


def shared_data_or_skip():
    """The folder of the real images (env CBC3D_SHARED_DATA); exits 77 (ctest: skipped) with a
    message where it is absent, as in a user's fresh clone."""
    import os

    shared = os.environ.get("CBC3D_SHARED_DATA", "")
    if not os.path.isdir(shared):
        print("SKIP: no shared data folder at %r (real images live in ../shared/data)" % shared)
        sys.exit(77)
    return shared


class Checks:
    """Collects failed checks; `finish()` prints the count and exits 1 if any failed."""

    def __init__(self):
        self.failures = []

    def __call__(self, condition, message):
        print(("ok   " if condition else "FAIL ") + message)
        if not condition:
            self.failures.append(message)
        return condition

    def finish(self):
        print("%d failed checks" % len(self.failures))
        sys.exit(1 if self.failures else 0)


def dihedral_angles(p):
    """Sorted dihedral angles in degrees of tets p with shape (tets, 4, 3)."""
    import numpy as np

    angles = []
    for a, b, c, d in [(0, 1, 2, 3), (1, 2, 0, 3), (2, 0, 1, 3), (0, 3, 1, 2), (1, 3, 0, 2), (2, 3, 0, 1)]:
        e = p[:, b] - p[:, a]
        e /= np.linalg.norm(e, axis=1)[:, None]
        u = p[:, c] - p[:, a]
        v = p[:, d] - p[:, a]
        u -= np.einsum("ij,ij->i", u, e)[:, None] * e
        v -= np.einsum("ij,ij->i", v, e)[:, None] * e
        angles.append(np.degrees(np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), np.einsum("ij,ij->i", u, v))))
    return np.sort(np.stack(angles, axis=1), axis=1)


def signed_volumes(points, tets):
    """Each tet's signed volume (positive when positively oriented), with numpy."""
    import numpy as np

    p = np.asarray(points, dtype=float)[np.asarray(tets)]
    return np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0])) / 6.0


# NIfTI-1 datatype codes and struct formats.
NIFTI_TYPES = {"uint8": (2, "B"), "int16": (4, "h"), "int32": (8, "i"), "float32": (16, "f"),
               "rgb24": (128, "BBB"), "uint32": (768, "I"), "int64": (1024, "q"), "uint64": (1280, "Q")}


def write_nifti(path, dims, values, dtype="int16", pixdim=(1.0, 1.0, 1.0, 1.0), qform_code=0,
                sform_code=0, quatern=(0, 0, 0), qoffset=(0, 0, 0),
                srows=((0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0))):
    """A 3-D NIfTI-1 file (.nii or .nii.gz). values: flat, x fastest (tuples for rgb24);
    pixdim = (qfac, dx, dy, dz)."""
    code, fmt = NIFTI_TYPES[dtype]
    header = bytearray(352)
    struct.pack_into("<i", header, 0, 348)
    struct.pack_into("<8h", header, 40, 3, dims[0], dims[1], dims[2], 1, 1, 1, 1)
    struct.pack_into("<hh", header, 70, code, 8 * struct.calcsize("<" + fmt))
    struct.pack_into("<8f", header, 76, *pixdim, 0, 0, 0, 0)
    struct.pack_into("<ff", header, 108, 352.0, 1.0)  # vox_offset, scl_slope
    struct.pack_into("<hh", header, 252, qform_code, sform_code)
    struct.pack_into("<6f", header, 256, *quatern, *qoffset)
    struct.pack_into("<12f", header, 280, *srows[0], *srows[1], *srows[2])
    header[344:348] = b"n+1\0"
    body = b"".join(struct.pack("<" + fmt, *(v if isinstance(v, tuple) else (v,))) for v in values)
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "wb") as f:
        f.write(bytes(header) + body)


def read_nifti_header(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rb") as f:
        raw = f.read(348)
    endian = "<" if struct.unpack("<i", raw[:4])[0] == 348 else ">"

    def field(fmt, offset):
        return struct.unpack_from(endian + fmt, raw, offset)

    return {
        "dim": field("8h", 40),
        "pixdim": field("8f", 76),
        "qform_code": field("h", 252)[0],
        "sform_code": field("h", 254)[0],
        "quatern": field("3f", 256),
        "qoffset": field("3f", 268),
        "srow": (field("4f", 280), field("4f", 296), field("4f", 312)),
    }


def kuhn_mesh(mask):
    """Each nonzero voxel of mask split into the 6 tets of the Kuhn triangulation (paths from its
    lowest to its highest corner), which conform across voxels, positively oriented; points on
    the voxel-corner grid (voxel i spans [i, i+1]); labels: the voxel values."""
    import itertools

    import numpy as np

    mask = np.asarray(mask)
    shape = np.array(mask.shape) + 1
    grid = np.stack(np.meshgrid(*[np.arange(s) for s in shape], indexing="ij"), axis=-1).reshape(-1, 3)
    voxels = np.argwhere(mask != 0)
    steps = np.eye(3, dtype=np.int64)
    tets = []
    for perm in itertools.permutations(range(3)):
        corners = [voxels]
        for axis in perm:
            corners.append(corners[-1] + steps[axis])
        tets.append(np.stack([(q[:, 0] * shape[1] + q[:, 1]) * shape[2] + q[:, 2] for q in corners], axis=1))
    tets = np.stack(tets, axis=1).reshape(-1, 4)
    points = grid.astype(float)
    p = points[tets]
    flip = np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0])) < 0
    tets[flip] = tets[flip][:, [1, 0, 2, 3]]
    return points, tets, np.repeat(mask[tuple(voxels.T)], 6)


def mpi_programs_or_skip(*programs):
    """The paths of mpiexec and the named programs (pvbatch, pvserver); exits 77 (skipped) with a
    message where one is missing."""
    import shutil

    paths = [shutil.which(name) for name in ("mpiexec",) + programs]
    if not all(paths):
        print("SKIP: %s not found" % ", ".join(n for n, p in zip(("mpiexec",) + programs, paths) if not p))
        sys.exit(77)
    return paths


def mpi_environment():
    """This process's environment for a child mpiexec: pvpython runs as an MPI singleton, and its
    OMPI_/PMIX_ variables would make mpiexec fail."""
    import os

    return {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "ORTE_"))}


def run_mpi_mesh(ranks, image, outputs, settings, timeout=600):
    """`mpiexec -n RANKS pvbatch mpi_mesh.py` on an image (the one-shot filter, SaveData to each
    output); its output in `.stdout`, stderr joined."""
    import os
    import subprocess

    mpiexec, pvbatch = mpi_programs_or_skip("pvbatch")
    driver = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mpi_mesh.py")
    command = [mpiexec, "--allow-run-as-root", "--oversubscribe", "-n", str(ranks), pvbatch, driver,
               os.environ["CBC3D_PLUGIN"], image] + outputs + settings
    return subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=timeout,
                          env=mpi_environment())


def read_msh(path):
    """Points, tets and each tet's tissue label (from the tissue_<label> physical names)."""
    import meshio
    import numpy as np

    mesh = meshio.read(path)
    label_of = {tag: int(name.split("_")[1]) for name, (tag, dim) in mesh.field_data.items()
                if name.startswith("tissue_") and dim == 3}
    tets, labels = [], []
    for block, tags in zip(mesh.cells, mesh.cell_data["gmsh:physical"]):
        if block.type == "tetra":
            tets.append(block.data)
            labels.append([label_of[t] for t in tags])
    return mesh.points, np.concatenate(tets), np.concatenate(labels)


def same_mesh(serial, parallel):
    """The largest distance from a parallel point to the nearest serial point, and the parallel
    tets that are not serial tets (points matched by position)."""
    import numpy as np
    from scipy.spatial import cKDTree

    distance, match = cKDTree(serial[0]).query(parallel[0])
    serial_tets = set(map(tuple, np.sort(serial[1], axis=1)))
    mapped = np.sort(match[parallel[1]], axis=1)
    return distance.max(), sum(tuple(t) not in serial_tets for t in mapped)


def conforming(tets):
    """Faces in more than two tets, and boundary edges not in exactly two boundary triangles."""
    import numpy as np

    faces = np.sort(np.concatenate([tets[:, [1, 2, 3]], tets[:, [0, 2, 3]], tets[:, [0, 1, 3]], tets[:, [0, 1, 2]]]), axis=1)
    unique, counts = np.unique(faces, axis=0, return_counts=True)
    boundary = unique[counts == 1]
    edges = np.sort(np.concatenate([boundary[:, [0, 1]], boundary[:, [1, 2]], boundary[:, [0, 2]]]), axis=1)
    _, edge_counts = np.unique(edges, axis=0, return_counts=True)
    return int((counts > 2).sum()), int((edge_counts != 2).sum())
