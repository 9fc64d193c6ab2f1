# Renders the pictures in Documentation/images with the CBC3D plugin:
#   xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython Documentation/MakePictures.py \
#     build/lib/paraview-5.11/plugins/CBC3D/CBC3D.so
# The real-image pictures need ../shared/data and are skipped without it. Names of pictures
# after the plugin (lattice-brain.png ...) render those alone. Tissues are coloured with a
# categorical map: one colour per label, named in the legend (picture_views.tissue_colours).
import os
import sys

from paraview.simple import *  # noqa: F401,F403

plugin = sys.argv[1] if len(sys.argv) > 1 else os.environ["CBC3D_PLUGIN"]
ALL = ["lattice-nested-shells.png", "lattice-brain.png", "lattice-three-tissues.png", "refined-three-tissues.png",
       "refined-nidus.png", "final-brain.png", "final-three-tissues.png", "sound-labels-brain.png"]
wanted = set(sys.argv[2:]) or set(ALL)
if wanted - set(ALL):
    sys.exit("MakePictures.py: unknown pictures %s (known: %s)" % (sorted(wanted - set(ALL)), ", ".join(ALL)))
LoadPlugin(plugin, remote=False, ns=globals())
here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
shared = os.path.join(root, "..", "shared", "data")
sys.path.insert(0, here)
from picture_views import (BRAIN, NESTED_SHELLS, THREE_TISSUES, middle_clip, tissue_colours,  # noqa: E402
                           tissue_legend, white_view)


def picture(image_path, edge, out_name, tissues=None, background=None, view_up=(0, 0, 1), direction=(1, -1, 0.6),
            refine=False, color_by="Label", final=False):
    """The lattice (or the refined mesh, or the whole method's) clipped by a plane through its
    centre, coloured by tissue (one colour per label, named in the legend: tissues, (label, name,
    colour) triples) or by another cell array (color_by, a continuous map)."""
    if out_name not in wanted:
        return
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
        lattice.BoundaryDistance = 0  # 3/8 of this lattice size, as on the command line
        if background is not None:
            lattice.BackgroundLabels = background
    lattice.UpdatePipeline()
    clip, centre, bounds = middle_clip(lattice)
    view = white_view([900, 700])
    for name in ("Label", "RefinementLevel"):  # bars of earlier pictures
        HideScalarBarIfNotNeeded(GetColorTransferFunction(name), view)
    display = Show(clip, view)
    display.SetRepresentationType("Surface With Edges")
    display.EdgeColor = [0.15, 0.15, 0.15]  # dark grey: ParaView's navy edges tint every colour blue
    ColorBy(display, ("CELLS", color_by))
    lut = GetColorTransferFunction(color_by)
    if color_by == "Label":
        tissue_colours(lut, tissues)
        display.SetScalarBarVisibility(view, True)
        tissue_legend(lut, view)
    else:
        lut.InterpretValuesAsCategories = 0
        display.RescaleTransferFunctionToDataRange(True)
        lut.ApplyPreset("Rainbow Uniform", True)
        value_range = lattice.CellData[color_by].GetRange()
        display.SetScalarBarVisibility(view, value_range[0] != value_range[1])
        bar = GetScalarBar(lut, view)
        bar.Visibility = int(value_range[0] != value_range[1])
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


def hinged_tets(mesh):
    """1 for the tets outside the largest face-connected piece of their tissue: with majority
    labels these hang on the rest by an edge or a vertex (counted by the independent checker)."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    sys.path.insert(0, os.path.join(root, "Testing", "Python"))
    import mesh_topology as mt

    tets = vtk_to_numpy(mesh.GetCells().GetConnectivityArray()).reshape(-1, 4).astype(np.int64)
    labels = vtk_to_numpy(mesh.GetCellData().GetArray("Label"))
    topology = mt.MeshTopology(vtk_to_numpy(mesh.GetPoints().GetData()), tets)
    same = labels[topology.pair_a] == labels[topology.pair_b]
    roots = mt.components(len(tets), topology.pair_a[same], topology.pair_b[same])
    flag = np.ones(len(tets), dtype=np.uint8)
    for label in np.unique(labels):
        mine = labels == label
        largest = np.bincount(roots[mine]).argmax()
        flag[mine & (roots == largest)] = 0
    return flag


def sound_labels_picture(image_path, edge, out_name, direction):
    """Majority labels (left) and sound labels (right): the brain's surface, with the tets that
    hang on the rest by an edge or a vertex in red."""
    if out_name not in wanted:
        return
    from paraview import servermanager
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid

    image = OpenDataFile(image_path)
    view = white_view([1400, 700])
    shown = []
    for side, sound in enumerate((0, 1)):
        lattice = CBC3DBCCLattice(Input=image)
        lattice.EdgeLength = edge
        refined = CBC3DRefinement(Input=lattice, Image=image)
        refined.SoundLabels = sound
        refined.UpdatePipeline()
        mesh = vtkUnstructuredGrid()
        mesh.ShallowCopy(servermanager.Fetch(refined))
        flag = numpy_to_vtk(hinged_tets(mesh), deep=1)
        flag.SetName("Hinged")
        mesh.GetCellData().AddArray(flag)
        producer = TrivialProducer()
        producer.GetClientSideObject().SetOutput(mesh)
        bounds = refined.GetDataInformation().GetBounds()
        shift = (bounds[1] - bounds[0]) * 1.15 * side
        body = Show(producer, view)
        body.Position = [shift, 0, 0]
        body.DiffuseColor = [0.85, 0.85, 0.8]
        body.AmbientColor = [0.85, 0.85, 0.8]
        body.ColorArrayName = ["POINTS", ""]
        body.Opacity = 0.35
        hinged = Threshold(Input=producer, Scalars=["CELLS", "Hinged"])
        try:
            hinged.LowerThreshold, hinged.UpperThreshold = 0.5, 1.5
        except AttributeError:
            hinged.ThresholdRange = [0.5, 1.5]
        red = Show(hinged, view)
        red.Position = [shift, 0, 0]
        red.ColorArrayName = ["POINTS", ""]
        red.DiffuseColor = [0.85, 0.1, 0.1]
        red.AmbientColor = [0.85, 0.1, 0.1]
        red.SetRepresentationType("Surface")
        red.Ambient = 0.5  # bright red, whatever the light
        shown += [hinged, producer, refined, lattice]
        print("%s labels: %d tets hang off their tissue's largest piece"
              % ("sound" if sound else "majority", int(vtk_array_sum(mesh.GetCellData().GetArray("Hinged")))))
    view.ResetCamera()
    camera = view.GetActiveCamera()
    focal = camera.GetFocalPoint()
    distance = camera.GetDistance()
    camera.SetPosition(*[focal[a] + distance * 0.9 * direction[a] for a in range(3)])
    camera.SetViewUp(0, 0, 1)
    view.ResetCamera()
    camera.Dolly(1.9)  # the two brains fill the picture
    Render(view)
    out = os.path.join(here, "images", out_name)
    SaveScreenshot(out, view, ImageResolution=[1400, 700])
    print("wrote", out)
    for proxy in shown + [image]:
        Delete(proxy)


def vtk_array_sum(array):
    return sum(array.GetTuple1(i) for i in range(array.GetNumberOfTuples()))


picture(os.path.join(root, "Data", "nested_shells.vti"), 2.0, "lattice-nested-shells.png", NESTED_SHELLS)
if os.path.isdir(shared):
    brain = os.path.join(shared, "cbc3d-brain.nii.gz")
    three = os.path.join(shared, "nipype-tissue-labels.nii.gz")
    picture(brain, 8.0, "lattice-brain.png", BRAIN, direction=(-1, -1, 0.6))
    picture(three, 6.0, "lattice-three-tissues.png", THREE_TISSUES)
    picture(three, 8.0, "refined-three-tissues.png", THREE_TISSUES, refine=True)
    picture(os.path.join(shared, "cbc3d-nidus.nii.gz"), 8.0, "refined-nidus.png", refine=True, direction=(1, -1, 1.2),
            color_by="RefinementLevel")
    picture(brain, 8.0, "final-brain.png", BRAIN, direction=(1, -0.5, 0.4), final=True)  # onto the cut
    picture(three, 8.0, "final-three-tissues.png", THREE_TISSUES, direction=(1, -0.5, 0.4), final=True)
    sound_labels_picture(os.path.join(shared, "cbc3d-brain.nii.gz"), 8.0, "sound-labels-brain.png", direction=(0, -1, 0.5))
else:
    print("no ../shared/data: real-image pictures skipped")
