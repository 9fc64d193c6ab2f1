# Plain python3: meshio (Debian's python3-meshio) reads every solver format cbc3d writes but XDMF
# (meshio reads one XDMF grid only; TestDolfinxReadsXdmf reads it) and the --surfaces file, from
# one run on Data/nested_shells.vti. Known answers come from the .vtu with numpy
# (export_expectations.py): the same points, the same tets with the same tissue per tet, the
# boundary and interface triangles per label pair with their names or documented ids, each
# oriented out of the tet behind it, and every tet positively oriented. The .feb is parsed as
# XML with the same counts. The Exodus II .exo is read by meshio (points, tets, a block per
# tissue) and its side sets with netCDF4 directly (names, ids, triangles per surface, each
# (element, side) the face of the tet behind the triangle, oriented out of it). Skips (77)
# without meshio, and after the other checks without netCDF4.
import json
import os
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks  # noqa: E402
import export_expectations as ex  # noqa: E402

try:
    import meshio
except ImportError:
    print("SKIP: meshio is not installed (Debian: python3-meshio)")
    sys.exit(77)
try:
    import netCDF4  # meshio's Exodus reader needs it too
except ImportError:
    netCDF4 = None

check = Checks()


def blocks(mesh, kind, key):
    """The cells of one type and their values of cell_data[key], concatenated."""
    cells = [c.data for c in mesh.cells if c.type == kind]
    values = [np.asarray(v).reshape(len(c.data), -1) for c, v in zip(mesh.cells, mesh.cell_data[key])
              if c.type == kind]
    return np.concatenate(cells), np.concatenate(values)


def check_tets(name, mesh, tets, labels, read_labels):
    """The file's tets and their tissues (read_labels) are the .vtu's, positively oriented."""
    read = np.concatenate([c.data for c in mesh.cells if c.type == "tetra"])
    check(np.allclose(mesh.points, points), "%s: the same %d points" % (name, len(points)))
    check(ex.tet_label_rows(read, read_labels) == ex.tet_label_rows(tets, labels),
          "%s: the same %d tets with the same tissue each (%s)" % (name, len(read), want["tissues"]))
    p = np.asarray(mesh.points)[read]
    volumes = np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]))
    check((volumes > 0).all(), "%s: every tet positively oriented" % name)


# Exodus II's 4-node TETRA sides as 0-based corners, in the spec's outward node order:
# 1 = (1,2,4), 2 = (2,3,4), 3 = (1,4,3), 4 = (1,3,2).
EXODUS_SIDES = {1: (0, 1, 3), 2: (1, 2, 3), 3: (0, 3, 2), 4: (0, 2, 1)}


def nc_names(nc, variable):
    value = nc.variables[variable]
    value.set_auto_mask(False)
    return [b"".join(row).decode().rstrip("\0") for row in value[:]]


def check_exodus(path):
    """meshio reads the points, the tets and a block per tissue; netCDF4 the side sets."""
    mesh = meshio.read(path)
    blocks_exo = [c.data for c in mesh.cells]
    check([c.type for c in mesh.cells] == ["tetra"] * len(want["tissues"]),
          "mesh.exo: meshio reads a tet block per tissue: %s" % [c.type for c in mesh.cells])
    with netCDF4.Dataset(path) as nc:
        block_names = nc_names(nc, "eb_names")
        block_ids = nc.variables["eb_prop1"][:].tolist()
        elem_types = [nc.variables["connect%d" % (k + 1)].elem_type for k in range(len(block_names))]
        check(block_names == ["tissue_%d" % k for k in want["tissues"]] and block_ids == list(want["tissues"])
              and elem_types == ["TETRA"] * len(block_names)
              and [len(nc.dimensions["num_nod_per_el%d" % (k + 1)]) for k in range(len(block_names))]
              == [4] * len(block_names),
              "mesh.exo: blocks %s, ids %s, %s" % (block_names, block_ids, sorted(set(elem_types))))
        block_labels = np.concatenate([np.full(len(b), k) for b, k in zip(blocks_exo, want["tissues"])])
        check_tets("mesh.exo", mesh, tets, labels, block_labels)
        elements = np.concatenate(blocks_exo)  # Exodus numbers the elements block after block
        names = nc_names(nc, "ss_names")
        ids = nc.variables["ss_prop1"][:].tolist()
        check(names == [want["names"][p] for p in sorted(want["ids"], key=want["ids"].get)]
              and ids == sorted(want["ids"].values()),
              "mesh.exo: a side set per surface in id order: %s, ids %s" % (names, ids))
        tet_index = {tuple(t): i for i, t in enumerate(np.asarray(tets).tolist())}
        for k, name in enumerate(names):
            pair = {n: p for p, n in want["names"].items()}.get(name)
            if pair is None:
                continue
            element = nc.variables["elem_ss%d" % (k + 1)][:] - 1
            side = nc.variables["side_ss%d" % (k + 1)][:]
            rows = np.array([elements[e][list(EXODUS_SIDES[int(s)])] for e, s in zip(element, side)])
            owners = [tet_index.get(tuple(elements[e].tolist()), -1) for e in element]
            wanted = sorted((tuple(f), t) for f, t in want["pairs"][pair])
            written = sorted((tuple(sorted(r)), t) for r, t in zip(rows.tolist(), owners))
            behind = ex.faces_behind_tets(points, tets, rows.tolist(), owners)
            check(written == wanted and behind == len(rows),
                  "mesh.exo: %s: %d (element, side) (expected %d), each the face of the tet behind "
                  "the triangle: %s, %d oriented out of it" % (name, len(rows), len(wanted),
                                                             written == wanted, behind))


def check_triangles(name, triangles, pair_of_row):
    """The triangles of each label pair are the expected faces, each oriented out of its tet."""
    for pair, faces in want["pairs"].items():
        rows = triangles[[pair_of_row(i) == pair for i in range(len(triangles))]]
        owner = dict(faces)
        same = sorted(tuple(sorted(r)) for r in rows.tolist()) == sorted(owner)
        behind = ex.faces_behind_tets(points, tets, rows.tolist(),
                                      [owner.get(tuple(sorted(r)), 0) for r in rows.tolist()])
        check(same and behind == len(rows), "%s: %s: %d triangles (expected %d), %d with their tet "
              "behind" % (name, ex.surface_name(pair), len(rows), len(faces), behind))


with tempfile.TemporaryDirectory() as work:
    outputs = ["mesh.msh", "mesh.inp", "mesh.mesh", "mesh.feb", "mesh.exo"]
    report = os.path.join(work, "report.json")
    points, tets, labels = ex.mesh_phantom(work, outputs, ["--surfaces", os.path.join(work, "surfaces.vtk"),
                                                           "--report", report])
    ex.mesh_phantom(work, ["mesh22.msh"], ["--msh-version", "2.2"])
    want = ex.expected(points, tets, labels)
    check(len(want["tissues"]) == 3 and len(want["pairs"]) >= 3,
          "the phantom has 3 tissues and %d surfaces: %s" % (len(want["pairs"]), sorted(want["names"].values())))
    pair_of_id = {i: p for p, i in want["ids"].items()}
    listed = {int(k): (v["name"], tuple(v["labels"]), v["triangles"])
              for k, v in json.load(open(report))["surfaces"].items()}
    check(listed == {want["ids"][p]: (want["names"][p], p, len(f)) for p, f in want["pairs"].items()},
          "the report lists every surface id with its name, labels and triangles: %s" % listed)

    for msh in ("mesh.msh", "mesh22.msh"):
        mesh = meshio.read(os.path.join(work, msh))
        tet_rows, tet_tags = blocks(mesh, "tetra", "gmsh:physical")
        check_tets(msh, mesh, tets, labels, tet_tags.ravel())
        names = {int(v[0]): k for k, v in mesh.field_data.items() if int(v[1]) == 2}
        pair_of_name = {n: p for p, n in want["names"].items()}
        tri_rows, tri_tags = blocks(mesh, "triangle", "gmsh:physical")
        check(sorted(names.values()) == sorted(want["names"].values()),
              "%s: the physical surfaces are named %s" % (msh, sorted(names.values())))
        check_triangles(msh, tri_rows, lambda i: pair_of_name.get(names.get(int(tri_tags[i, 0]))))
        volumes = {k for k, v in mesh.field_data.items() if int(v[1]) == 3}
        check(volumes == {"tissue_%d" % k for k in want["tissues"]}, "%s: physical volumes %s" % (msh, sorted(volumes)))

    mesh = meshio.read(os.path.join(work, "mesh.mesh"))
    tet_rows, refs = blocks(mesh, "tetra", "medit:ref")
    check_tets("mesh.mesh", mesh, tets, labels, refs.ravel())
    tri_rows, tri_refs = blocks(mesh, "triangle", "medit:ref")
    check_triangles("mesh.mesh", tri_rows, lambda i: pair_of_id.get(int(tri_refs[i, 0])))

    mesh = meshio.read(os.path.join(work, "mesh.inp"))
    read = np.concatenate([c.data for c in mesh.cells if c.type == "tetra"])
    set_labels = np.zeros(len(read), dtype=np.int64)
    for label in want["tissues"]:
        set_labels[np.concatenate(mesh.cell_sets["tissue_%d" % label])] = label
    check_tets("mesh.inp", mesh, tets, labels, set_labels)
    text = open(os.path.join(work, "mesh.inp")).read()
    surfaces = sorted(line.split("NAME=")[1] for line in text.splitlines() if line.startswith("*SURFACE"))
    check(surfaces == sorted(want["names"].values()), "mesh.inp: a *SURFACE per pair: %s" % surfaces)

    mesh = meshio.read(os.path.join(work, "surfaces.vtk"))
    tri_rows, sides = blocks(mesh, "triangle", "BoundaryLabels")
    # The surfaces file holds only the points it uses: compare by coordinates.
    index = {tuple(p): i for i, p in enumerate(np.round(points, 9).tolist())}
    rows = np.array([[index[tuple(q)] for q in np.round(mesh.points[r], 9).tolist()] for r in tri_rows])
    check(sides.shape[1] == 2, "surfaces.vtk: BoundaryLabels has 2 components")
    check_triangles("surfaces.vtk", rows, lambda i: (int(sides[i, 0]), int(sides[i, 1])))

    root = ElementTree.parse(os.path.join(work, "mesh.feb")).getroot()
    check(root.tag == "febio_spec" and root.get("version") == "4.0", "mesh.feb: febio_spec 4.0")
    check(len(root.findall("Mesh/Nodes/node")) == len(points), "mesh.feb: %d nodes" % len(points))
    blocks_feb = {e.get("name"): len(e) for e in root.findall("Mesh/Elements") if e.get("type") == "tet4"}
    check(blocks_feb == {"tissue_%d" % k: v for k, v in want["tissues"].items()},
          "mesh.feb: a tet4 block per tissue with its tets: %s" % blocks_feb)
    surfaces_feb = {e.get("name"): len(e.findall("tri3")) for e in root.findall("Mesh/Surface")}
    check(surfaces_feb == {want["names"][p]: len(f) for p, f in want["pairs"].items()},
          "mesh.feb: a Surface per pair with its triangles: %s" % surfaces_feb)
    domains = {d.get("name"): d.get("mat") for d in root.findall("MeshDomains/SolidDomain")}
    materials = {m.get("name") for m in root.findall("Material/material")}
    check(set(domains) == set(blocks_feb) and set(domains.values()) == materials,
          "mesh.feb: a SolidDomain per tissue, each with its placeholder material: %s" % domains)

    if netCDF4 is not None:
        check_exodus(os.path.join(work, "mesh.exo"))
if netCDF4 is None and not check.failures:
    print("SKIP: the .exo checks need netCDF4 (Debian: python3-netcdf4); the other formats passed")
    sys.exit(77)
check.finish()
