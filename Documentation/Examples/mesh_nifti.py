"""Mesh a NIfTI label image with the whole CBC3D method, from pvpython.

    pvpython Documentation/Examples/mesh_nifti.py PLUGIN.so IMAGE.nii.gz OUT.vtu [SCREENSHOT.png]
             [--edge-length MM] [--fidelity F] [--iterations N] [--background L ...]
             [--name L=NAME ...]

PLUGIN.so: the CBC3D plugin (build/lib/paraview-5.11/plugins/CBC3D/CBC3D.so, or
<prefix>/lib/paraview-5.11/plugins/CBC3D/CBC3D.so once installed). The image is read with the
plugin's NIfTI reader (world frame, RAS millimetres) and meshed by the one-shot filter
"CBC3D Image To Mesh" (proxy CBC3DImageToMesh), which runs the whole method with the
command line's defaults: the BCC lattice, red-green refinement to the voxel fidelity and the
boundary distance, deformation onto the image boundaries (dihedral angles kept within
[20, 160] degrees, tissue volumes kept), then the quality figures against the image. The
figures are printed, and the mesh is written to OUT.vtu (VTK XML, inline binary, zlib).

With SCREENSHOT.png, the mesh is also clipped through its centre (whole tets: a crinkle clip),
coloured by tissue with a categorical map (one colour per label, named in the legend: "label 2",
or the name given by --name 2=CSF) and rendered to that file. Rendering needs a display; on a
server: `xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython ...` (without -noreset, Xvfb
may reset just as the render window connects and pvpython aborts with "bad X server
connection").

Exits 1 with a message when the plugin, the image or the meshing fails.

Where the stage filters fit. The one-shot filter is the chain below; build it instead of
CBC3DImageToMesh to look at (Show, clip, colour by RefinementLevel or Displacement) the output
of each stage, in pvpython or in ParaView's Filters > CBC3D menu:

    lattice = CBC3DBCCLattice(Input=image)                   # 1. BCC lattice ("CBC3D BCC Lattice")
    lattice.EdgeLength = 8.0                                 #    mm; 0: 8 x the finest voxel spacing
    refined = CBC3DRefinement(Input=lattice, Image=image)    # 2. red-green refinement ("CBC3D Refinement")
    refined.BoundaryDistance = 0                             #    0: 3/8 of the lattice edge
    deformed = CBC3DDeformation(Input=refined, Image=image)  # 3. deformation ("CBC3D Deformation")
    quality = CBC3DMeshQuality(Input=deformed, Image=image)  # 4. angles, distances, topology ("CBC3D Mesh Quality")

Set BackgroundLabels on each of them alike. The lattice alone (quality straight after step 1)
is a staircase of 60 and 90 degree angles whose Hausdorff distance is about the lattice edge:
not the method's mesh.
"""
import argparse
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

# One colour per tissue (Okabe-Ito's colour-blind safe set, then a few more); repeats after 12.
PALETTE = [(0.90, 0.62, 0.00), (0.34, 0.71, 0.91), (0.00, 0.62, 0.45), (0.94, 0.89, 0.26),
           (0.00, 0.45, 0.70), (0.84, 0.37, 0.00), (0.80, 0.47, 0.65), (0.60, 0.60, 0.60),
           (0.55, 0.34, 0.16), (0.60, 0.85, 0.55), (0.45, 0.30, 0.65), (0.95, 0.65, 0.70)]


def parse_arguments():
    parser = argparse.ArgumentParser(description="Mesh a NIfTI label image with the CBC3D plugin.")
    parser.add_argument("plugin", help="the CBC3D plugin, CBC3D.so")
    parser.add_argument("image", help="a label image, .nii or .nii.gz (any format ParaView reads will do)")
    parser.add_argument("output", help="the mesh, .vtu")
    parser.add_argument("screenshot", nargs="?", help="optional: a picture of the clipped mesh, .png")
    parser.add_argument("--edge-length", type=float, default=0.0,
                        help="lattice cube edge in mm (default 0: 8 x the finest voxel spacing)")
    parser.add_argument("--fidelity", type=float, default=0.95,
                        help="voxel fidelity every tissue reaches (default 0.95; 0: no refinement)")
    parser.add_argument("--iterations", type=int, default=5,
                        help="deformation iterations (default 5; 0: no deformation)")
    parser.add_argument("--background", type=int, action="append",
                        help="a label that is not tissue (repeatable; default 0)")
    parser.add_argument("--name", action="append", default=[], metavar="L=NAME",
                        help="the legend's name for label L (repeatable; default 'label L')")
    args = parser.parse_args()
    args.names = {}
    for item in args.name:
        label, sep, name = item.partition("=")
        try:
            args.names[int(label)] = name
        except ValueError:
            sep = ""
        if not sep or not name:
            parser.error("--name takes LABEL=NAME, got " + item)
    return args


def fail(message):
    print("mesh_nifti.py: error: " + message, file=sys.stderr)
    sys.exit(1)


def field_values(fields, name):
    array = fields.GetArray(name)
    if array is None:
        return []
    return [array.GetTuple1(i) for i in range(array.GetNumberOfTuples())]


def print_quality(mesh):
    """The figures the one-shot filter leaves in the field data (vtkCBC3DArrayNames.h)."""
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
               "TissueHausdorffDistance", "TissueHausdorffDistance95", "TissueMeanSurfaceDistance",
               "TissueVolume", "TissueImageVolume"]
    table = [field_values(fields, name) for name in columns]
    print("%8s %8s %9s %9s %10s %8s %8s %8s" % ("tissue", "tets", "min deg", "max deg", "Hausdorff", "95%",
                                                 "mean", "volume"))
    for row in zip(*table):
        label, tets, low, high, hausdorff, h95, mean, volume, image_volume = row
        share = "%7.1f%%" % (100.0 * volume / image_volume) if image_volume > 0 else "       -"
        print("%8d %8d %9.2f %9.2f %10.3f %8.3f %8.3f %s" % (label, tets, low, high, hausdorff, h95, mean, share))
    passes, iterations = field_values(fields, "RefinementPasses"), field_values(fields, "DeformationIterations")
    print("refinement: %s passes; deformation: %s iterations; %s" % (
        "%d" % passes[0] if passes else "no", "%d" % iterations[0] if iterations else "no",
        "ready for a solver" if one("SolverReady") == 1 else "NOT ready for a solver (hinges or non-manifold parts)"))


def tissue_colours(lut, labels, names):
    """A categorical map: one colour per label, each named in the legend (not a continuous bar
    running from the smallest label to the largest)."""
    lut.InterpretValuesAsCategories = 1
    lut.AnnotationsInitialized = 1
    lut.Annotations = [text for label in labels for text in ("%d" % label, names.get(label, "label %d" % label))]
    lut.IndexedColors = [c for i in range(len(labels)) for c in PALETTE[i % len(PALETTE)]]


def save_screenshot(mesh_proxy, labels, names, path):
    """The mesh clipped by the plane x = centre (whole tets), one colour per tissue."""
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
    display.EdgeColor = [0.15, 0.15, 0.15]
    ColorBy(display, ("CELLS", "Label"))
    lut = GetColorTransferFunction("Label")
    tissue_colours(lut, labels, names)
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = "tissue"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]   # dark on the white background
    bar.TitleFontSize = bar.LabelFontSize = 16
    bar.TextPosition = "Ticks left/bottom, annotations right/top"
    size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
    camera = view.GetActiveCamera()
    camera.SetFocalPoint(*centre)
    camera.SetPosition(centre[0] + 2.4 * size, centre[1] - 1.1 * size, centre[2] + 0.9 * size)
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
    if "CBC3DImageToMesh" not in globals():
        fail(args.plugin + " is not the CBC3D plugin")

    image = OpenDataFile(args.image)   # .nii/.nii.gz: the plugin's CBC3D NIfTI reader
    if image is None:
        fail("no reader for " + args.image)
    # The whole method in one filter: lattice, refinement, deformation, quality (the module
    # comment shows the same chain stage by stage).
    mesher = CBC3DImageToMesh(Input=image)
    mesher.LatticeSize = args.edge_length      # 0: 8 x the finest voxel spacing
    # The panel fills in the automatic sizes of the image when the filter is made; 0 makes them
    # follow the lattice size set above, as the command line's defaults do.
    mesher.BoundaryDistance = 0                # 3/8 of the lattice edge
    mesher.MinimumEdgeLength = 0               # the voxel size
    mesher.Fidelity = args.fidelity
    mesher.DeformationIterations = args.iterations
    if args.background:
        mesher.BackgroundLabels = args.background
    mesher.UpdatePipeline()
    mesh = servermanager.Fetch(mesher)
    if mesh is None or mesh.GetNumberOfCells() == 0:
        fail("no mesh (see the messages above)")
    edge = field_values(mesh.GetFieldData(), "LatticeEdgeLength")
    print("%s: lattice edge %.3f mm" % (args.image, edge[0] if edge else float("nan")))
    print_quality(mesh)

    # Inline binary, zlib: the writer's default appended mode does not read back with Debian 12's
    # expat once the file is over about 4 KB. (SaveData("OUT.msh", proxy=mesher) writes the
    # solver formats: .msh, .inp, .mesh, .feb, .xdmf, .exo.)
    SaveData(args.output, proxy=mesher, DataMode="Binary", CompressorType="ZLib")
    print("wrote", args.output)

    if args.screenshot:
        labels = [int(label) for label in field_values(mesh.GetFieldData(), "TissueLabel")]
        save_screenshot(mesher, labels, args.names, args.screenshot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
