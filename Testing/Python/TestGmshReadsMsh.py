# Plain python3: Gmsh's own Python API (Debian's python3-gmsh) opens the .msh cbc3d writes, in
# 4.1 and 2.2, and lists the named physical groups: tissue_<label> volumes (tag = label) with
# their tets, boundary_<label> and interface_<a>_<b> surfaces with their triangles; counts from
# the .vtu with numpy (export_expectations.py). Skips (77) without gmsh.
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cbc3d_testing import Checks  # noqa: E402
import export_expectations as ex  # noqa: E402

try:
    import gmsh
except ImportError:
    print("SKIP: gmsh's Python API is not installed (Debian: python3-gmsh)")
    sys.exit(77)

check = Checks()


def physical_groups(path):
    """{(dim, name): (tag, element count)} of the file's physical groups, as Gmsh reads them."""
    gmsh.open(path)
    groups = {}
    for dim, tag in gmsh.model.getPhysicalGroups():
        name = gmsh.model.getPhysicalName(dim, tag)
        count = 0
        for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            _, element_tags, _ = gmsh.model.mesh.getElements(dim, entity)
            count += sum(len(t) for t in element_tags)
        groups[(dim, name)] = (tag, count)
    return groups


gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
with tempfile.TemporaryDirectory() as work:
    points, tets, labels = ex.mesh_phantom(work, ["mesh.msh"])
    ex.mesh_phantom(work, ["mesh22.msh"], ["--msh-version", "2.2"])
    want = ex.expected(points, tets, labels)
    expected = {(3, "tissue_%d" % k): (k, n) for k, n in want["tissues"].items()}
    expected.update({(2, want["names"][p]): (want["ids"][p], len(f)) for p, f in want["pairs"].items()})
    for name in ("mesh.msh", "mesh22.msh"):
        path = os.path.join(work, name)
        try:
            groups = physical_groups(path)
        except Exception as error:
            check(False, "%s: gmsh opens it (%s)" % (name, error))
            continue
        volumes = gmsh.model.getEntities(3)
        check(len(volumes) == len(want["tissues"]), "%s: gmsh opens it: %d volume entities" % (name, len(volumes)))
        check(groups == expected, "%s: physical groups (dim, name): (tag, elements) %s"
              % (name, sorted(groups.items())))
        nodes, _, _ = gmsh.model.mesh.getNodes()
        check(len(nodes) == len(points), "%s: %d nodes (the .vtu has %d)" % (name, len(nodes), len(points)))
        gmsh.clear()
gmsh.finalize()
check.finish()
