# Run by the ParaView GUI (not pvpython) from Testing/Gui/TestParaViewGui.py:
#   xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" paraview --dr --script=gui_script.py --exit
# Loads the CBC3D plugin, opens Data/nested_shells.vti, applies CBC3D Image To Mesh (lattice 4 mm),
# clips it through the centre keeping whole tets (crinkle), colours it by Label in the GUI's
# render view and saves a screenshot. Paths come from the environment: CBC3D_PLUGIN,
# CBC3D_SOURCE_DIR, CBC3D_GUI_SCREENSHOT. Writes CBC3D_GUI_SCREENSHOT + ".txt" with
# "cells N" last, so the driver knows the script ran to the end.
import os

from paraview.simple import *  # noqa: F401,F403

plugin = os.environ["CBC3D_PLUGIN"]
source = os.environ["CBC3D_SOURCE_DIR"]
screenshot = os.environ["CBC3D_GUI_SCREENSHOT"]

LoadPlugin(plugin, remote=False, ns=globals())
image = OpenDataFile(os.path.join(source, "Data", "nested_shells.vti"))
lattice = CBC3DImageToMesh(Input=image)  # the one-shot filter: all stages
lattice.LatticeSize = 4.0
lattice.UpdatePipeline()
cells = lattice.GetDataInformation().GetNumberOfCells()
bounds = lattice.GetDataInformation().GetBounds()
centre = [(bounds[2 * a] + bounds[2 * a + 1]) / 2 for a in range(3)]

clip = Clip(Input=lattice)
clip.ClipType = "Plane"
clip.ClipType.Origin = centre
clip.ClipType.Normal = [1, 0, 0]
clip.Crinkleclip = 1

view = GetActiveViewOrCreate("RenderView")   # the GUI's own render view
display = Show(clip, view)
Hide3DWidgets(proxy=clip.ClipType)           # no plane widget in the picture
display.SetRepresentationType("Surface With Edges")
ColorBy(display, ("CELLS", "Label"))
display.RescaleTransferFunctionToDataRange(True)
GetColorTransferFunction("Label").ApplyPreset("Rainbow Uniform", True)
display.SetScalarBarVisibility(view, True)
camera = view.GetActiveCamera()
camera.SetFocalPoint(*centre)
camera.SetPosition(centre[0] + 60, centre[1] - 60, centre[2] + 40)
camera.SetViewUp(0, 0, 1)
view.ResetCamera()
Render(view)
SaveScreenshot(screenshot, view, ImageResolution=[800, 600])
with open(screenshot + ".txt", "w") as f:
    f.write("lattice cells %d\nclip cells %d\n" % (cells, clip.GetDataInformation().GetNumberOfCells()))
    f.write("cells %d\n" % cells)
