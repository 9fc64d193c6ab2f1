"""The main job on a bundled phantom: summary, JSON report, .vtu and .vtk outputs, --quiet."""
import json
import os
import subprocess
import sys
import tempfile

CLI = os.environ["CBC3D_CLI"]
SOURCE = os.environ["CBC3D_SOURCE_DIR"]
PHANTOM = os.path.join(SOURCE, "Data", "nested_shells.vti")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from cbc3d_testing import Checks  # noqa: E402

check = Checks()


def run(*args):
    return subprocess.run([CLI] + list(args), capture_output=True, text=True, timeout=300)


with tempfile.TemporaryDirectory() as work:
    vtu = os.path.join(work, "shells.vtu")
    report_path = os.path.join(work, "shells.json")
    result = run(PHANTOM, "-o", vtu, "--bcc-size", "2", "--fidelity", "0", "--iterations", "0",
                 "--report", report_path)
    check(result.returncode == 0, "main job exits 0 (stderr: %r)" % result.stderr)
    check(result.stderr == "", "lattice-only run prints nothing on stderr when not on a terminal")
    report = json.load(open(report_path))
    for key in ("tetrahedra", "points", "min_dihedral_deg", "max_dihedral_deg", "seconds", "tissues"):
        check(key in report, "report has %s" % key)
    check(report["tetrahedra"] > 0 and report["points"] > 0, "mesh is not empty")
    check(abs(report["min_dihedral_deg"] - 60.0) < 0.01, "min dihedral 60 degrees")
    check(abs(report["max_dihedral_deg"] - 90.0) < 0.01, "max dihedral 90 degrees")
    check(sorted(report["tissues"]) == ["1", "2", "3"], "tissues keyed by label value 1 2 3")
    check(sum(t["tetrahedra"] for t in report["tissues"].values()) == report["tetrahedra"],
          "tissue tet counts add up")
    check(report["parameters"]["bcc_size_mm"] == 2.0, "report records the lattice size")
    check(report["parameters"]["keep_volumes"] is True, "report records volume keeping (on by default)")
    # Fidelity: the lattice is within a lattice cell of the shells, never exactly on them.
    hd = report["hausdorff_mm"]
    check(isinstance(hd, float) and 0.0 < hd <= 2.0 * 3 ** 0.5, "hausdorff_mm %r within one lattice cube diagonal" % hd)
    check(hd == max(t["hausdorff_mm"] for t in report["tissues"].values()), "mesh Hausdorff is the largest tissue's")
    for label, tissue in report["tissues"].items():
        check(max(tissue["mesh_to_image_mm"], tissue["image_to_mesh_mm"]) == tissue["hausdorff_mm"]
              and tissue["mean_distance_mm"] <= tissue["hausdorff_95_mm"] <= tissue["hausdorff_mm"],
              "tissue %s: one-sided, 95th percentile and mean distances are consistent" % label)
        check(tissue["tetrahedra_under_10_deg"] == 0 and tissue["tetrahedra_over_170_deg"] == 0,
              "tissue %s: no tets under 10 or over 170 degrees" % label)
        check(0.8 < tissue["volume_mm3"] / tissue["image_volume_mm3"] < 1.2,
              "tissue %s: mesh volume %.0f mm3 near the image's %.0f mm3"
              % (label, tissue["volume_mm3"], tissue["image_volume_mm3"]))
    for key in ("volume_mm3", "image_volume_mm3"):
        total = sum(t[key] for t in report["tissues"].values())
        check(abs(report[key] - total) <= 1e-9 * total, "mesh %s is the tissues' sum" % key)
    check(all(k in report["seconds"] for k in ("read", "lattice", "total")), "seconds per stage")
    # The summary on stdout gives the same figures as the report.
    check("tetrahedra %d, points %d" % (report["tetrahedra"], report["points"]) in result.stdout,
          "summary prints tets and points")
    for label in ("1", "2", "3"):
        check(any(line.split()[:1] == [label] for line in result.stdout.splitlines()),
              "summary has a row for tissue " + label)
    # Topology: the image's Euler characteristics are the phantom's design (tissues 1 and 2
    # hollow shells, 3 a ball, all of them together a ball); the mesh's figures agree with each
    # other and with the summary's verdict.
    topology_keys = ("face_components", "vertex_components", "hinged_parts", "nonmanifold_edges",
                     "nonmanifold_vertices", "surface_euler", "image_surface_euler")
    topology = report.get("topology", {})
    check(all(k in topology for k in topology_keys) and isinstance(topology.get("solver_ready"), bool),
          "report has a topology object: %r" % topology)
    check(topology.get("image_surface_euler") == 2, "whole body's image Euler characteristic is 2 (a ball)")
    for label, euler in (("1", 4), ("2", 4), ("3", 2)):
        tissue = report["tissues"][label]
        check(all(k in tissue for k in topology_keys), "tissue %s has the topology keys" % label)
        check(tissue.get("image_surface_euler") == euler,
              "tissue %s: image Euler characteristic %r, expected %d" % (label, tissue.get("image_surface_euler"), euler))
        check(tissue.get("hinged_parts") == tissue.get("face_components", 0) - tissue.get("vertex_components", 0),
              "tissue %s: hinged parts are face minus vertex components" % label)
        joined, parted = tissue.get("image_surface_euler_pinches_joined"), tissue.get("image_surface_euler_pinches_parted")
        # The phantom's shells have no voxels touching only along an edge or at a corner: a
        # manifold surface round them has their voxel-face figure either way.
        check(joined == euler and parted == euler,
              "tissue %s: the manifold readings %r (pinches joined) and %r (parted) are the image's %d"
              % (label, joined, parted, euler))
    if all(k in topology for k in topology_keys):
        tissues = report["tissues"].values()
        ready = (topology["hinged_parts"] == 0 and topology["nonmanifold_edges"] == 0
                 and topology["nonmanifold_vertices"] == 0 and all(t["hinged_parts"] == 0 for t in tissues))
        check(topology["solver_ready"] == ready, "solver_ready %r matches the counts" % topology["solver_ready"])
        check(topology["nonmanifold_edges"] >= sum(t["nonmanifold_edges"] for t in tissues),
              "the mesh's non-manifold edges include every tissue's")
        verdict = [line for line in result.stdout.splitlines() if line.strip().startswith("topology:")]
        check(len(verdict) == 1 and verdict[0].endswith(
            (": ready for a solver" if ready else ": NOT ready for a solver"))
              and ("Euler %d (image 2)" % topology["surface_euler"]) in verdict[0],
              "summary prints the topology verdict: %r" % verdict)
    # Inline binary, never appended (VTK 9.2 cannot read appended files here).
    text = open(vtu, "rb").read()
    check(b'format="binary"' in text and b'format="appended"' not in text, ".vtu is inline binary")

    vtk = os.path.join(work, "shells.vtk")
    result = run(PHANTOM, "-o", vtk, "--bcc-size", "2", "--quiet")
    check(result.returncode == 0 and result.stdout == "" and result.stderr == "",
          "--quiet prints nothing (stdout %r, stderr %r)" % (result.stdout, result.stderr))
    check(open(vtk, "rb").read(30).startswith(b"# vtk DataFile Version 4.2"), ".vtk is legacy 4.2")

    # Default parameters: lattice, refinement to F 0.95, 5 deformation iterations, quality.
    default_report = os.path.join(work, "default.json")
    result = run(PHANTOM, "-o", os.path.join(work, "default.vtu"), "--report", default_report)
    check(result.returncode == 0 and result.stderr == "", "default run exits 0 quietly (%r)" % result.stderr)
    check("lattice size 8.000 mm" in result.stdout, "default lattice size is 8 x 1 mm")
    default = json.load(open(default_report))
    check(all(stage in default["seconds"] for stage in ("lattice", "refinement", "deformation", "quality")),
          "default run has every stage: %s" % sorted(default["seconds"]))
    check(default["inverted_tetrahedra"] == 0 and default["min_dihedral_deg"] >= 10 - 1e-9,
          "default mesh: no inverted tet, angles >= 10 degrees")
    check(all("fidelity_f1" in t for t in default["tissues"].values()), "default report has F1/F2 per tissue")
    # Deformation ends by keeping volumes (the default): each shell within 3% of its voxels'.
    for label, tissue in default["tissues"].items():
        check(abs(tissue["volume_mm3"] / tissue["image_volume_mm3"] - 1.0) < 0.03,
              "default run, tissue %s: mesh volume %.0f mm3 within 3%% of the image's %.0f mm3"
              % (label, tissue["volume_mm3"], tissue["image_volume_mm3"]))
    check(abs(default["refinement"]["boundary_distance_mm"] - 3.0) < 1e-9,
          "default boundary distance is 3/8 of the 8 mm lattice: %r" % default["refinement"])
    unbound_report = os.path.join(work, "unbound.json")
    result = run(PHANTOM, "-o", os.path.join(work, "unbound.vtu"), "--boundary-distance", "-1",
                 "--report", unbound_report)
    unbound = json.load(open(unbound_report))
    check(result.returncode == 0 and unbound["refinement"]["boundary_distance_mm"] == 0
          and unbound["tetrahedra"] <= default["tetrahedra"],
          "--boundary-distance -1 turns the bound off (%d tets, bounded %d)" % (unbound["tetrahedra"], default["tetrahedra"]))

    result = run("--help")
    check(result.returncode == 0 and "--bcc-size" in result.stdout, "--help")
    check([f for f in os.listdir(work) if ".part-" in f] == [], "no temporary files left")

check.finish()
