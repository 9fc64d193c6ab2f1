# Renders Documentation/images/size-budgets-nyhead.png, the New York Head (1 mm) at three tet
# budgets, clipped through its middle, one colour per tissue:
#   xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython Documentation/MakeSizePictures.py \
#     build/lib/paraview-5.11/plugins/CBC3D/CBC3D.so
# Needs ../shared/data; says so and stops without it.
import os
import sys

from paraview.simple import *  # noqa: F401,F403

plugin = sys.argv[1] if len(sys.argv) > 1 else os.environ["CBC3D_PLUGIN"]
LoadPlugin(plugin, remote=False, ns=globals())
here = os.path.dirname(os.path.abspath(__file__))
head = os.path.join(here, "..", "..", "shared", "data", "nyhead-6tissue-1mm.nii.gz")
sys.path.insert(0, here)
from picture_views import NEW_YORK_HEAD, middle_clip, tissue_colours, white  # noqa: E402

if not os.path.exists(head):
    print("skipped: %s is absent" % head)
    sys.exit(0)
BUDGETS = (50000, 300000, 1000000)

image = OpenDataFile(head)
layout = CreateLayout("budgets")
layout.SplitHorizontal(0, 1.0 / 3.0)
layout.SplitHorizontal(2, 0.5)
CELLS = (1, 5, 6)  # the layout's three cells, left to right
LEGEND_SHIFT = -0.5  # of the head's depth: how far the first view looks beside it
views = []
for i, budget in enumerate(BUDGETS):
    mesher = CBC3DImageToMesh(Input=image)
    mesher.MaximumNumberOfTets = budget
    # Automatic, as on the command line: the budget may make the lattice coarser, and the
    # boundary distance follows the lattice (the panel fills in the values for no budget).
    mesher.LatticeSize = 0
    mesher.BoundaryDistance = 0
    mesher.UpdatePipeline()
    tets = mesher.GetDataInformation().GetNumberOfCells()
    clip, centre, bounds = middle_clip(mesher)
    view = white(CreateView("RenderView"))
    AssignViewToLayout(view=view, layout=layout, hint=CELLS[i])
    display = Show(clip, view)
    display.SetRepresentationType("Surface With Edges")
    display.EdgeColor = [0.15, 0.15, 0.15]
    ColorBy(display, ("CELLS", "Label"))
    lut = GetColorTransferFunction("Label")
    tissue_colours(lut, NEW_YORK_HEAD)  # one colour per tissue, named in the legend
    display.SetScalarBarVisibility(view, i == 0)
    if i == 0:
        bar = GetScalarBar(lut, view)
        bar.Title = "tissue"
        bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
        bar.TitleFontSize = bar.LabelFontSize = 14
        bar.WindowLocation = "Any Location"
        bar.Position = [0.05, 0.3]
        bar.TextPosition = "Ticks left/bottom, annotations right/top"
    title = Text(Text="--max-tets %d: %d tets" % (budget, tets))
    text = Show(title, view)
    text.Color = [0.1, 0.1, 0.1]
    text.FontSize = 18
    text.WindowLocation = "Upper Center"
    camera = view.GetActiveCamera()
    camera.SetFocalPoint(*centre)
    camera.SetPosition(centre[0] + 600, centre[1], centre[2])
    camera.SetViewUp(0, 0, 1)
    view.ResetCamera()
    camera.Dolly(0.75)
    if i == 0:  # the first head moves right, leaving room for the legend
        shift = LEGEND_SHIFT * (bounds[3] - bounds[2])
        camera.SetFocalPoint(*[centre[0], centre[1] + shift, centre[2]])
        position = camera.GetPosition()
        camera.SetPosition(position[0], position[1] + shift, position[2])
    views.append(view)
# Each view is zoomed to its clip: the same head fills each third.
out = os.path.join(here, "images", "size-budgets-nyhead.png")
SaveScreenshot(out, layout, SaveAllViews=1, ImageResolution=[2100, 760])
print("wrote", out)
