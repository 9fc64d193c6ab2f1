"""Renders images/keep-volumes-ventricles.png: one axial slice of the shared ventricles image
with the outline of cbc3d's mesh cut through it, meshed with --keep-volumes off and on (the
default). Debian's python3 with numpy, matplotlib and ParaView's VTK:

    /usr/bin/python3 Documentation/MakeVolumePicture.py build/bin/cbc3d ../shared/data/cbc3d-ventricles.nii.gz
"""
import json
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "Testing", "Python"))
from cbc3d_testing import read_nifti_header  # noqa: E402
import mesh_topology as mt  # noqa: E402


def outline(mesh_path, origin, normal):
    """Line segments (n, 2, 3) where the mesh's outer surface crosses the plane."""
    from vtkmodules.vtkCommonDataModel import vtkPlane
    from vtkmodules.vtkFiltersCore import vtkCutter
    from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    from vtkmodules.util.numpy_support import vtk_to_numpy

    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(mesh_path)
    surface = vtkGeometryFilter()
    surface.SetInputConnection(reader.GetOutputPort())
    plane = vtkPlane()
    plane.SetOrigin(*origin)
    plane.SetNormal(*normal)
    cutter = vtkCutter()
    cutter.SetInputConnection(surface.GetOutputPort())
    cutter.SetCutFunction(plane)
    cutter.Update()
    lines = cutter.GetOutput()
    points = vtk_to_numpy(lines.GetPoints().GetData())
    connectivity = vtk_to_numpy(lines.GetLines().GetConnectivityArray()).reshape(-1, 2)
    return points[connectivity]


def main():
    cli, image_path = sys.argv[1], sys.argv[2]
    out = os.path.join(HERE, "images", "keep-volumes-ventricles.png")
    labels = mt.read_nifti(image_path)
    srow = np.array(read_nifti_header(image_path)["srow"])
    affine = np.vstack([srow, [0, 0, 0, 1]])  # voxel index -> world (mm)
    tissue = np.argwhere(labels > 0)
    k = int(np.bincount(tissue[:, 2]).argmax())  # the axial slice with the most tissue
    origin = affine @ np.array([0, 0, k, 1.0])
    normal = affine[:3, 2] / np.linalg.norm(affine[:3, 2])
    to_index = np.linalg.inv(affine)
    low, high = tissue.min(axis=0)[:2] - 6, tissue.max(axis=0)[:2] + 6
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.8), gridspec_kw={"width_ratios": [1.35, 1]})
    colours = {"off": "#c0392b", "on": "#1e8449"}
    cuts, shares = {}, {}
    with tempfile.TemporaryDirectory() as work:
        for keep in ("off", "on"):
            mesh = os.path.join(work, "ventricles-%s.vtu" % keep)
            report = os.path.join(work, "ventricles-%s.json" % keep)
            subprocess.run([cli, image_path, "-o", mesh, "--keep-volumes", keep, "--quiet", "--report", report],
                           check=True)
            tissue_report = json.load(open(report))["tissues"]["128"]
            shares[keep] = tissue_report["volume_mm3"] / tissue_report["image_volume_mm3"]
            cuts[keep] = [(to_index @ np.c_[segment, np.ones(2)].T)[:2] for segment in outline(mesh, origin[:3], normal)]
    # The whole slice, and a close-up of its upper left part (the thin hook of this slice).
    size = high - low
    windows = [(low, high), (low + np.array([0.0, 0.5]) * size, low + np.array([0.42, 0.92]) * size)]
    for ax, (lo, hi) in zip(axes, windows):
        ax.imshow(labels[:, :, k].T > 0, cmap="Greys", origin="lower", vmin=0, vmax=2.2,
                  extent=(-0.5, labels.shape[0] - 0.5, -0.5, labels.shape[1] - 0.5))
        for keep in ("off", "on"):
            for n, ij in enumerate(cuts[keep]):
                ax.plot(ij[0], ij[1], color=colours[keep], linewidth=1.3,
                        label=None if n else "--keep-volumes %s: %.1f%% of the voxels' volume" % (keep, 100.0 * shares[keep]))
        ax.set_xlim(lo[0] - 0.5, hi[0] - 0.5)
        ax.set_ylim(lo[1] - 0.5, hi[1] - 0.5)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
    axes[0].legend(loc="lower left", fontsize=9)
    axes[1].set_title("close-up (upper left): each grey square is a 1 mm voxel")
    fig.suptitle("Lateral ventricles (1 mm voxels, grey), axial slice %d, and the mesh's surface cut there" % k)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main()
