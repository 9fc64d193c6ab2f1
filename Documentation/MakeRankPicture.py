"""The picture of "Meshing on a cluster": the 3 mm head meshed on 3 ranks without deformation,
each rank's tets in its own colour (ParaView's Process Id Scalars).

    xvfb-run -a mpiexec -n 3 pvbatch Documentation/MakeRankPicture.py PLUGIN IMAGE OUTPUT.png

IMAGE: ../shared/data/nipype-tissue-labels.nii.gz for the guide's picture.
"""
import sys

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, LoadPlugin, ProcessIdScalars,
                             SaveScreenshot, Show)

plugin, image_file, output = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
image = globals()["CBC3DNIfTIReader"](FileName=image_file)
mesh = globals()["CBC3DImageToMesh"](Input=image)
mesh.DeformationIterations = 0
ranks = ProcessIdScalars(Input=mesh)
view = CreateView("RenderView")
view.ViewSize = [900, 700]
view.Background = [1, 1, 1]
view.OrientationAxesVisibility = 0
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
display = Show(ranks, view)
display.Representation = "Surface With Edges"
display.EdgeColor = [0.2, 0.2, 0.2]
ColorBy(display, ("POINTS", "ProcessId"))
colours = GetColorTransferFunction("ProcessId")
colours.InterpretValuesAsCategories = 1
colours.Annotations = ["0", "rank 0", "1", "rank 1", "2", "rank 2"]
colours.IndexedColors = [0.85, 0.37, 0.01, 0.11, 0.62, 0.47, 0.46, 0.44, 0.70]
display.SetScalarBarVisibility(view, False)
view.ResetCamera()
camera = view.GetActiveCamera()
camera.Azimuth(60)
camera.Elevation(20)
view.ResetCamera()
SaveScreenshot(output, view, ImageResolution=[900, 700])
