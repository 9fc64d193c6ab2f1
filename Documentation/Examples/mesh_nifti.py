"""Mesh a NIfTI label image with the CBC3D ParaView plugin, from pvpython.

    pvpython Documentation/Examples/mesh_nifti.py PLUGIN.so IMAGE.nii.gz OUT.vtu [SCREENSHOT.png]
             [--edge-length MM] [--background L ...]

PLUGIN.so: the CBC3D plugin (build/lib/paraview-5.11/plugins/CBC3D/CBC3D.so, or
<prefix>/lib/paraview-5.11/plugins/CBC3D/CBC3D.so once installed). The image is read with the
plugin's NIfTI reader (world frame, RAS millimetres), meshed with the BCC lattice filter,
measured with the quality filter against the image, and the mesh is written to OUT.vtu
(VTK XML, inline binary, zlib). The quality figures are printed. With SCREENSHOT.png, the mesh
is also clipped through its centre (whole tets: a crinkle clip), coloured by tissue label and
rendered to that file; rendering needs a display (on a server:
`xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython ...`; without -noreset, Xvfb may
reset just as the render window connects and pvpython aborts with "bad X server connection").
Exits 1 with a message when the plugin, the image or the meshing fails.
"""
import argparse
import math
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager


def parse_arguments():
    parser = argparse.ArgumentParser(description="Mesh a NIfTI label image with the CBC3D plugin.")
    parser.add_argument("plugin", help="the CBC3D plugin, CBC3D.so")
    parser.add_argument("image", help="a label image, .nii or .nii.gz (any format ParaView reads will do)")
    parser.add_argument("output", help="the mesh, .vtu")
    parser.add_argument("screenshot", nargs="?", help="optional: a picture of the clipped mesh, .png")
    parser.add_argument("--edge-length", type=float, default=0.0,
                        help="lattice cube edge in mm (default 0: 8 x the finest voxel spacing)")
    parser.add_argument("--background", type=int, action="append",
                        help="a label that is not tissue (repeatable; default 0)")
    return parser.parse_args()


def fail(message):
    print("mesh_nifti.py: error: " + message, file=sys.stderr)
    sys.exit(1)


def field_values(fields, name):
    array = fields.GetArray(name)
    if array is None:
        return []
    return [array.GetTuple1(i) for i in range(array.GetNumberOfTuples())]


def print_quality(mesh):
    """The figures vtkCBC3DMeshQuality leaves in the field data (see its class comment)."""
    fields = mesh.GetFieldData()

    def one(name):
        values = field_values(fields, name)
        return values[0] if values else float("nan")

    print("tetrahedra %d, points %d, inverted %d" % (mesh.GetNumberOfCells(), mesh.GetNumberOfPoints(),
                                                     one("InvertedTetCount")))
    print("dihedral angles %.2f to %.2f degrees; %d tets under 10, %d over 170" % (
        one("MinDihedralAngle"), one("MaxDihedralAngle"), one("SmallAngleTetCount"), one("LargeAngleTetCount")))
    print("Hausdorff distance %.3f mm (95%%: %.3f, mean %.3f)" % (
        one("HausdorffDistance"), one("HausdorffDistance95"), one("MeanSurfaceDistance")))
    columns = ["TissueLabel", "TissueTetCount", "TissueMinDihedralAngle", "TissueMaxDihedralAngle",
               "TissueHausdorffDistance", "TissueHausdorffDistance95", "TissueMeanSurfaceDistance"]
    table = [field_values(fields, name) for name in columns]
    print("%8s %8s %9s %9s %10s %8s %8s" % ("tissue", "tets", "min deg", "max deg", "Hausdorff", "95%", "mean"))
    for row in zip(*table):
        label, tets, low, high, hausdorff, h95, mean = row
        print("%8d %8d %9.2f %9.2f %10.3f %8.3f %8.3f" % (label, tets, low, high, hausdorff, h95, mean))


def save_screenshot(mesh_proxy, path):
    """The mesh clipped by the plane x = centre (whole tets), coloured by Label."""
    bounds = mesh_proxy.GetDataInformation().GetBounds()
    centre = [(bounds[2 * a] + bounds[2 * a + 1]) / 2 for a in range(3)]
    clip = Clip(Input=mesh_proxy)
    clip.ClipType = "Plane"
    clip.ClipType.Origin = centre
    clip.ClipType.Normal = [1, 0, 0]
    clip.Crinkleclip = 1
    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = [800, 600]
    view.OrientationAxesVisibility = 0
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.Background = [1, 1, 1]
    display = Show(clip, view)
    display.SetRepresentationType("Surface With Edges")
    ColorBy(display, ("CELLS", "Label"))
    display.RescaleTransferFunctionToDataRange(True)
    lut = GetColorTransferFunction("Label")
    lut.ApplyPreset("Rainbow Uniform", True)
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = "Label"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]   # dark on the white background
    bar.RangeLabelFormat = "%.0f"
    size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
    camera = view.GetActiveCamera()
    camera.SetFocalPoint(*centre)
    camera.SetPosition(centre[0] + 2.2 * size, centre[1] - 2.2 * size, centre[2] + 1.3 * size)
    camera.SetViewUp(0, 0, 1)
    view.ResetCamera()
    Render(view)
    SaveScreenshot(path, view, ImageResolution=[800, 600])
    # Delete the view before the script ends: with the view still alive at sys.exit, pvpython
    # 5.11 under Xvfb dies at exit with "GLXBadContext" (exit code 1).
    Delete(clip)
    Delete(view)
    print("wrote", path)


def main():
    args = parse_arguments()
    if not os.path.isfile(args.plugin):
        fail("no plugin file " + args.plugin)
    if not os.path.isfile(args.image):
        fail("no image file " + args.image)
    if not args.output.endswith(".vtu"):
        fail("the output must be a .vtu file: " + args.output)
    LoadPlugin(args.plugin, remote=False, ns=globals())
    if "CBC3DBCCLattice" not in globals():
        fail(args.plugin + " is not the CBC3D plugin")

    image = OpenDataFile(args.image)   # .nii/.nii.gz: the plugin's CBC3D NIfTI reader
    if image is None:
        fail("no reader for " + args.image)
    lattice = CBC3DBCCLattice(Input=image)
    lattice.EdgeLength = args.edge_length
    quality = CBC3DMeshQuality(Input=lattice, Image=image)
    if args.background:
        lattice.BackgroundLabels = args.background
        quality.BackgroundLabels = args.background
    quality.UpdatePipeline()
    mesh = servermanager.Fetch(quality)
    if mesh is None or mesh.GetNumberOfCells() == 0:
        fail("no mesh (see the messages above)")
    edge = field_values(mesh.GetFieldData(), "LatticeEdgeLength")
    print("%s: lattice edge %.3f mm" % (args.image, edge[0] if edge else float("nan")))
    print_quality(mesh)

    # Inline binary, zlib: the writer's default appended mode does not read back with Debian 12's
    # expat once the file is over about 4 KB.
    SaveData(args.output, proxy=quality, DataMode="Binary", CompressorType="ZLib")
    print("wrote", args.output)

    if args.screenshot:
        save_screenshot(quality, args.screenshot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
