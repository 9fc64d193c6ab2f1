# Renders the pictures in Documentation/images with the CBC3D plugin:
#   xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython Documentation/MakePictures.py \
#     build/lib/paraview-5.11/plugins/CBC3D/CBC3D.so
# The real-image pictures need ../shared/data and are skipped without it.
import os
import sys

from paraview.simple import *  # noqa: F401,F403

plugin = sys.argv[1] if len(sys.argv) > 1 else os.environ["CBC3D_PLUGIN"]
LoadPlugin(plugin, remote=False, ns=globals())
here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
shared = os.path.join(root, "..", "shared", "data")


def picture(image_path, edge, out_name, background=None, view_up=(0, 0, 1), direction=(1, -1, 0.6),
            refine=False, color_by="Label", final=False):
    """The lattice (or the refined mesh) clipped by a plane through its centre, coloured by Label."""
    image = OpenDataFile(image_path)
    lattice = CBC3DBCCLattice(Input=image)
    lattice.EdgeLength = edge
    if background is not None:
        lattice.BackgroundLabels = background
    if refine:
        lattice = CBC3DRefinement(Input=lattice, Image=image)
        if background is not None:
            lattice.BackgroundLabels = background
    if final:
        lattice = CBC3DImageToMesh(Input=image)
        lattice.LatticeSize = edge
        if background is not None:
            lattice.BackgroundLabels = background
    lattice.UpdatePipeline()
    bounds = lattice.GetDataInformation().GetBounds()
    centre = [(bounds[2 * a] + bounds[2 * a + 1]) / 2 for a in range(3)]
    clip = Clip(Input=lattice)
    clip.ClipType = "Plane"
    clip.ClipType.Origin = centre
    clip.ClipType.Normal = [1, 0, 0]
    clip.Crinkleclip = 1  # whole tets, as in the paper's cross-sections
    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = [900, 700]
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    for name in ("Label", "RefinementLevel"):  # bars of earlier pictures
        HideScalarBarIfNotNeeded(GetColorTransferFunction(name), view)
    display = Show(clip, view)
    display.SetRepresentationType("Surface With Edges")
    ColorBy(display, ("CELLS", color_by))
    display.RescaleTransferFunctionToDataRange(True)
    lut = GetColorTransferFunction(color_by)
    lut.ApplyPreset("Rainbow Uniform", True)
    label_range = lattice.CellData[color_by].GetRange()
    display.SetScalarBarVisibility(view, label_range[0] != label_range[1])
    bar = GetScalarBar(lut, view)
    bar.Visibility = int(label_range[0] != label_range[1])
    bar.Title = color_by
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.TitleFontSize = bar.LabelFontSize = 20
    bar.RangeLabelFormat = "%-#.0f"
    view.ResetCamera()
    camera = view.GetActiveCamera()
    camera.SetFocalPoint(*centre)
    size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
    camera.SetPosition(*[centre[a] + 2.2 * size * direction[a] for a in range(3)])
    camera.SetViewUp(*view_up)
    view.ResetCamera()
    Render(view)
    out = os.path.join(here, "images", out_name)
    SaveScreenshot(out, view, ImageResolution=[900, 700])
    print("wrote", out)
    for proxy in (clip, lattice, image):
        Delete(proxy)


picture(os.path.join(root, "Data", "nested_shells.vti"), 2.0, "lattice-nested-shells.png")
if os.path.isdir(shared):
    picture(os.path.join(shared, "cbc3d-brain.nii.gz"), 8.0, "lattice-brain.png", direction=(-1, -1, 0.6))
    picture(os.path.join(shared, "nipype-tissue-labels.nii.gz"), 6.0, "lattice-three-tissues.png")
    picture(os.path.join(shared, "nipype-tissue-labels.nii.gz"), 8.0, "refined-three-tissues.png", refine=True)
    picture(os.path.join(shared, "cbc3d-nidus.nii.gz"), 8.0, "refined-nidus.png", refine=True, direction=(1, -1, 1.2),
            color_by="RefinementLevel")
    picture(os.path.join(shared, "cbc3d-brain.nii.gz"), 8.0, "final-brain.png", direction=(-1, -1, 0.6), final=True)
    picture(os.path.join(shared, "nipype-tissue-labels.nii.gz"), 8.0, "final-three-tissues.png", final=True)
else:
    print("no ../shared/data: real-image pictures skipped")
