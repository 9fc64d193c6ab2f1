"""What the solver formats must hold for a mesh, computed with numpy from the .vtu alone (not
from cbc3d's own tagging): the tets per tissue, and the boundary and interface triangles per
label pair with the tet behind each. Shared by the export round-trip tests."""
import os
import subprocess

import numpy as np

import mesh_topology as mt

OUTSIDE = 0  # the outside label: the first background label, 0 by default


def surface_name(pair):
    a, b = pair
    return "boundary_%d" % a if b == OUTSIDE else "interface_%d_%d" % (a, b)


def expected(points, tets, labels):
    """{"tissues": {label: tet count}, "pairs": {(a, b): [(sorted face, owning tet), ...]},
    "ids": {(a, b): surface id}, "names": {(a, b): name}} where a is the tet behind the face:
    the tissue of a boundary face, the lower label of an interface."""
    faces = {}
    for t, tet in enumerate(tets):
        for skip in range(4):
            key = tuple(sorted(np.delete(tet, skip).tolist()))
            faces.setdefault(key, []).append(t)
    pairs = {}
    for key, owners in faces.items():
        if len(owners) == 1:
            pairs.setdefault((int(labels[owners[0]]), OUTSIDE), []).append((key, owners[0]))
        elif labels[owners[0]] != labels[owners[1]]:
            low = min(owners, key=lambda t: labels[t])
            high = max(owners, key=lambda t: labels[t])
            pairs.setdefault((int(labels[low]), int(labels[high])), []).append((key, low))
    # Documented order: the boundaries by tissue, then the interfaces by (a, b); ids from 1.
    order = sorted(pairs, key=lambda p: (p[1] != OUTSIDE, p[0], p[1]))
    tissues = {int(k): int(v) for k, v in zip(*np.unique(labels, return_counts=True))}
    return {"tissues": tissues, "pairs": pairs, "ids": {p: i + 1 for i, p in enumerate(order)},
            "names": {p: surface_name(p) for p in order}}


def faces_behind_tets(points, tets, triangles, owners):
    """How many oriented triangles have their owning tet behind them (normal pointing away from
    the tet's fourth vertex), as the formats promise."""
    good = 0
    for tri, t in zip(triangles, owners):
        fourth = [v for v in tets[t] if v not in tri][0]
        p0, p1, p2 = points[list(tri)]
        good += np.dot(np.cross(p1 - p0, p2 - p0), points[fourth] - p0) < 0
    return good


def mesh_phantom(work, outputs, extra=()):
    """Meshes Data/nested_shells.vti (3 tissues, --bcc-size 4) into work/mesh.vtu plus
    `outputs`; returns (points, tets, labels) of the .vtu and the run."""
    cli = os.environ["CBC3D_CLI"]
    phantom = os.path.join(os.environ["CBC3D_SOURCE_DIR"], "Data", "nested_shells.vti")
    args = [cli, phantom, "--bcc-size", "4", "--quiet", "-o", os.path.join(work, "mesh.vtu")]
    for out in outputs:
        args += ["-o", os.path.join(work, out)]
    run = subprocess.run(args + list(extra), capture_output=True, text=True, timeout=300)
    if run.returncode != 0:
        raise RuntimeError("cbc3d failed: %s" % run.stderr.strip())
    return mt.read_mesh(os.path.join(work, "mesh.vtu"))


def tet_label_rows(tets, labels):
    """The multiset of (tet as written, label) rows, for comparing files that order tets
    differently."""
    return sorted(zip(map(tuple, np.asarray(tets).tolist()), np.asarray(labels).tolist()))
