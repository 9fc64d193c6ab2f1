"""An independent checker of the topology of a labelled tetrahedral mesh, in numpy alone (none of
cbc3d's code), and of the label image it was made from.

Mesh, for each tissue and for the whole mesh (all tets):
  - face-connected and vertex-connected components of the tets (their difference: hinged parts,
    pieces that hang on the rest by an edge or a vertex only);
  - the surface: mesh faces with exactly one tet of the tissue (outside the mesh is background);
  - non-manifold edges (surface edges in more than two surface triangles) and non-manifold
    vertices (surface vertices whose triangles form more than one fan, triangles being linked
    when they share an edge through the vertex);
  - the surface's Euler characteristic V - E + F.
Image, for each tissue: the Euler characteristic of its voxel-face surface (voxels as unit
cubes, the image border counting as outside) and its 6-connected components.

    python3 mesh_topology.py MESH.vtu [IMAGE.nii.gz [--background L]...]

Reads .vtu/.vtk with VTK's Python modules (Debian's python3-paraview gives them to plain
python3; meshio cannot read cbc3d's string field data) and NIfTI with the standard library.
"""
import gzip
import os
import struct
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import read_nifti_header  # noqa: E402


# ---------------------------------------------------------------------------------------------
# Connected components: union-find in numpy (hook roots onto the smaller root, then jump
# pointers until every node points at a root), so that 10^6 nodes take well under a second.

def components(n, a, b):
    """Root of each of nodes 0..n-1 in the graph with edges (a[i], b[i]); roots are the smallest
    node of each component."""
    parent = np.arange(n, dtype=np.int64)
    a = np.asarray(a, dtype=np.int64)
    b = np.asarray(b, dtype=np.int64)
    while True:
        ra, rb = parent[a], parent[b]
        differ = ra != rb
        if not differ.any():
            return parent
        lo = np.minimum(ra[differ], rb[differ])
        hi = np.maximum(ra[differ], rb[differ])
        # Each root hi takes the smallest root it is linked to: roots only move to smaller
        # ones, so no cycle forms and the loop ends (the smallest keeps the rounds few).
        order = np.argsort(hi * n + lo)
        hi, lo = hi[order], lo[order]
        first = np.ones(len(hi), dtype=bool)
        first[1:] = hi[1:] != hi[:-1]
        parent[hi[first]] = lo[first]
        while True:
            grand = parent[parent]
            if np.array_equal(grand, parent):
                break
            parent = grand
        a, b = a[differ], b[differ]  # edges already inside one component stay there


def count_components(roots, nodes):
    return int(np.unique(roots[nodes]).size) if len(nodes) else 0


# ---------------------------------------------------------------------------------------------
# Mesh

TET_FACES = np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])
TRI_EDGES = np.array([[0, 1], [1, 2], [2, 0]])


def row_ids(rows):
    """Ids 0..k-1 of the distinct rows of a non-negative integer array, and the distinct rows."""
    rows = np.ascontiguousarray(rows, dtype=np.int64)
    base = int(rows.max()) + 1 if rows.size else 1
    if base ** rows.shape[1] < 2 ** 62:
        # One int64 key per row: sorting integers is far faster than sorting records.
        key = np.zeros(len(rows), dtype=np.int64)
        for column in range(rows.shape[1]):
            key = key * base + rows[:, column]
        _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
        return inverse.ravel(), rows[first]
    unique, inverse = np.unique(rows.view([("", np.int64)] * rows.shape[1]).ravel(), return_inverse=True)
    return inverse.ravel(), unique.view(np.int64).reshape(-1, rows.shape[1])


class MeshTopology:
    """Faces of a tet mesh computed once; `part(mask)` measures any set of its tets."""

    def __init__(self, points, tets):
        self.points = np.asarray(points, dtype=float)
        self.tets = np.asarray(tets, dtype=np.int64)
        self.n_points = len(self.points)
        m = len(self.tets)
        faces = np.sort(self.tets[:, TET_FACES].reshape(-1, 3), axis=1)
        face_of, self.faces = row_ids(faces)
        self.face_of = face_of.reshape(m, 4)  # face id of each tet's four faces
        uses = np.bincount(self.face_of.ravel(), minlength=len(self.faces))
        self.crowded_faces = int((uses > 2).sum())  # a conforming mesh has none
        # Tet pairs across interior faces: sort the tet faces by face id; equal neighbours pair up.
        order = np.argsort(self.face_of.ravel(), kind="stable")
        sorted_faces = self.face_of.ravel()[order]
        same = np.nonzero(sorted_faces[1:] == sorted_faces[:-1])[0]
        self.pair_a = order[same] // 4
        self.pair_b = order[same + 1] // 4

    def part(self, mask):
        """Topology figures of the tets where mask is true."""
        mask = np.asarray(mask, dtype=bool)
        tets = np.nonzero(mask)[0]
        m = len(self.tets)
        # Face components: tets of the part linked through the faces they share.
        inside = mask[self.pair_a] & mask[self.pair_b]
        roots = components(m, self.pair_a[inside], self.pair_b[inside])
        face_components = count_components(roots, tets)
        # Vertex components: the points of each tet of the part linked together; a tet lies in
        # the component of its first point.
        corners = self.tets[tets]
        roots = components(self.n_points, np.repeat(corners[:, 0], 3), corners[:, 1:].ravel())
        vertex_components = count_components(roots, corners[:, 0])
        # Surface: faces with exactly one tet of the part (outside the mesh counts as not).
        uses = np.bincount(self.face_of[tets].ravel(), minlength=len(self.faces))
        triangles = self.faces[uses == 1]
        surface = surface_topology(triangles)
        surface.update(tets=len(tets), face_components=face_components,
                       vertex_components=vertex_components,
                       hinged=face_components - vertex_components)
        return surface


def surface_topology(triangles):
    """V, E, F, Euler characteristic, non-manifold edges and vertices of a triangle set."""
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    f = len(triangles)
    if f == 0:
        return dict(V=0, E=0, F=0, euler=0, nonmanifold_edges=0, nonmanifold_vertices=0)
    # Each triangle side, as (triangle, low vertex, high vertex).
    sides = np.sort(triangles[:, TRI_EDGES].reshape(-1, 2), axis=1)
    edge_of, edges = row_ids(sides)
    edge_uses = np.bincount(edge_of)
    vertices = np.unique(triangles)
    # Fans: one node per (triangle, corner). At each side's two end points, the nodes of the
    # triangles that share that side are linked (a chain over the triangles of the edge).
    corner_node = (np.arange(f)[:, None] * 3 + np.arange(3)[None, :])  # node of corner c of t
    # For side (t, i->j) the end points are corners i and j of triangle t.
    ends = TRI_EDGES  # corner indices of each side's end points
    node_at = np.stack([corner_node[:, ends[:, 0]].ravel(), corner_node[:, ends[:, 1]].ravel()], axis=1)
    vert_at = np.stack([triangles[:, ends[:, 0]].ravel(), triangles[:, ends[:, 1]].ravel()], axis=1)
    # Records: (edge id, vertex, node), for both end points of every side.
    rec_edge = np.concatenate([edge_of, edge_of])
    rec_vert = np.concatenate([vert_at[:, 0], vert_at[:, 1]])
    rec_node = np.concatenate([node_at[:, 0], node_at[:, 1]])
    order = np.lexsort((rec_node, rec_vert, rec_edge))
    e, v, nd = rec_edge[order], rec_vert[order], rec_node[order]
    link = np.nonzero((e[1:] == e[:-1]) & (v[1:] == v[:-1]))[0]
    roots = components(3 * f, nd[link], nd[link + 1])
    # Fans at a vertex: distinct roots among its corner nodes.
    _, fan = row_ids(np.stack([triangles.ravel(), roots[corner_node.ravel()]], axis=1))
    fans_per_vertex = np.bincount(fan[:, 0])
    return dict(V=int(len(vertices)), E=int(len(edges)), F=int(f),
                euler=int(len(vertices) - len(edges) + f),
                nonmanifold_edges=int((edge_uses > 2).sum()),
                nonmanifold_vertices=int((fans_per_vertex > 1).sum()))


def mesh_report(points, tets, labels):
    """{label: figures} for each tissue label, and under "all" for the whole mesh."""
    topo = MeshTopology(points, tets)
    labels = np.asarray(labels).ravel()
    report = {int(label): topo.part(labels == label) for label in np.unique(labels)}
    report["all"] = topo.part(np.ones(len(tets), dtype=bool))
    report["all"]["crowded_faces"] = topo.crowded_faces
    return report


def read_mesh(path):
    """points (n, 3), tets (m, 4) and the Label cell array of a .vtu or .vtk mesh, via VTK."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    if path.endswith(".vtu"):
        from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader as Reader
    else:
        from vtkmodules.vtkIOLegacy import vtkUnstructuredGridReader as Reader
    reader = Reader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid is None or grid.GetNumberOfCells() == 0:
        raise RuntimeError("no cells read from %s" % path)
    types = vtk_to_numpy(grid.GetCellTypesArray())
    if not np.all(types == 10):  # VTK_TETRA
        raise RuntimeError("%s holds cells other than tets" % path)
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    tets = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4).astype(np.int64)
    labels = vtk_to_numpy(grid.GetCellData().GetArray("Label")).astype(np.int64)
    return points, tets, labels


# ---------------------------------------------------------------------------------------------
# Image

NIFTI_DTYPES = {2: "u1", 4: "i2", 8: "i4", 16: "f4", 64: "f8", 256: "i1", 512: "u2", 768: "u4",
                1024: "i8", 1280: "u8"}


def read_nifti(path):
    """The voxel values of a 3-D NIfTI-1 image as an (nx, ny, nz) array, scaled by scl_slope
    and scl_inter where the slope is set (the standard's rule)."""
    header = read_nifti_header(path)
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rb") as f:
        raw = f.read()
    endian = "<" if struct.unpack("<i", raw[:4])[0] == 348 else ">"
    datatype = struct.unpack_from(endian + "h", raw, 70)[0]
    offset = int(struct.unpack_from(endian + "f", raw, 108)[0])
    slope, inter = struct.unpack_from(endian + "ff", raw, 112)
    nx, ny, nz = header["dim"][1:4]
    dtype = np.dtype(endian + NIFTI_DTYPES[datatype])
    values = np.frombuffer(raw, dtype=dtype, count=nx * ny * nz, offset=offset)
    values = values.reshape(nz, ny, nx).transpose(2, 1, 0)  # x varies fastest in the file
    if slope not in (0.0, 1.0) or inter != 0.0:
        values = values * (slope if slope else 1.0) + inter
    return values


def voxel_components(mask):
    """Sizes of the 6-connected components of a boolean 3-D array (largest first)."""
    mask = np.asarray(mask, dtype=bool)
    index = -np.ones(mask.shape, dtype=np.int64)
    index[mask] = np.arange(int(mask.sum()))
    a, b = [], []
    for axis in range(3):
        lo = [slice(None)] * 3
        hi = [slice(None)] * 3
        lo[axis] = slice(0, -1)
        hi[axis] = slice(1, None)
        both = mask[tuple(lo)] & mask[tuple(hi)]
        a.append(index[tuple(lo)][both])
        b.append(index[tuple(hi)][both])
    n = int(mask.sum())
    roots = components(n, np.concatenate(a), np.concatenate(b))
    return np.sort(np.bincount(np.unique(roots, return_inverse=True)[1]))[::-1] if n else np.zeros(0, int)


def voxel_surface_euler(mask):
    """V - E + F of the faces between voxels of mask and voxels not in it (the border counting
    as outside), V and E being the distinct voxel corners and grid edges of those faces."""
    padded = np.pad(np.asarray(mask, dtype=bool), 1)
    shape = np.array(padded.shape) + 1  # the grid of voxel corners
    corner_id = lambda c: (c[:, 0] * shape[1] + c[:, 1]) * shape[2] + c[:, 2]  # noqa: E731
    corners, edges, faces = [], [], 0
    for axis in range(3):
        u, w = [d for d in range(3) if d != axis]
        lo = [slice(None)] * 3
        hi = [slice(None)] * 3
        lo[axis] = slice(0, -1)
        hi[axis] = slice(1, None)
        # A face of normal `axis` between voxel i and i+1 lies on corner plane i+1.
        where = np.argwhere(padded[tuple(lo)] != padded[tuple(hi)])
        where[:, axis] += 1
        faces += len(where)
        du = np.zeros(3, dtype=np.int64)
        dw = np.zeros(3, dtype=np.int64)
        du[u] = 1
        dw[w] = 1
        for c in (where, where + du, where + dw, where + du + dw):
            corners.append(corner_id(c))
        # Its four sides: along u from the corner and from corner + dw, along w from the corner
        # and from corner + du; an edge is (start corner, direction).
        edges.append(corner_id(where) * 3 + u)
        edges.append(corner_id(where + dw) * 3 + u)
        edges.append(corner_id(where) * 3 + w)
        edges.append(corner_id(where + du) * 3 + w)
    if faces == 0:
        return 0
    v = np.unique(np.concatenate(corners)).size
    e = np.unique(np.concatenate(edges)).size
    return int(v - e + faces)


def image_report(values, background=(0,), minimum_voxels=8):
    """{label: figures} for each tissue of a label image and, under "all", for the union of
    its tissues."""
    values = np.asarray(values)
    labels = [int(v) for v in np.unique(values) if int(v) not in set(background)]
    report = {}
    for label in labels + ["all"]:
        mask = np.isin(values, labels) if label == "all" else values == label
        sizes = voxel_components(mask)
        report[label] = dict(voxels=int(mask.sum()), components=int(len(sizes)),
                             components_kept=int((sizes >= minimum_voxels).sum()),
                             euler=voxel_surface_euler(mask))
    return report


# ---------------------------------------------------------------------------------------------

def format_mesh(name, r):
    return ("%s: %d tets, face components %d, vertex components %d, hinged %d, surface V %d E %d "
            "F %d Euler %d, non-manifold edges %d, vertices %d"
            % (name, r["tets"], r["face_components"], r["vertex_components"], r["hinged"], r["V"],
               r["E"], r["F"], r["euler"], r["nonmanifold_edges"], r["nonmanifold_vertices"]))


def format_image(name, r):
    return ("%s: %d voxels, 6-connected components %d (%d of 8+ voxels), voxel surface Euler %d"
            % (name, r["voxels"], r["components"], r["components_kept"], r["euler"]))


def main(argv):
    import argparse
    import time

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mesh")
    parser.add_argument("image", nargs="?")
    parser.add_argument("--background", type=int, action="append")
    args = parser.parse_args(argv)
    start = time.time()
    points, tets, labels = read_mesh(args.mesh)
    report = mesh_report(points, tets, labels)
    for key, r in report.items():
        print(format_mesh("mesh tissue %s" % key if key != "all" else "mesh (all tets)", r))
    print("faces in 3+ tets: %d" % report["all"]["crowded_faces"])
    if args.image:
        image = image_report(read_nifti(args.image), background=args.background or [0])
        for key, r in image.items():
            print(format_image("image tissue %s" % key if key != "all" else "image (all tissues)", r))
    print("%.2f s" % (time.time() - start))


if __name__ == "__main__":
    main(sys.argv[1:])
