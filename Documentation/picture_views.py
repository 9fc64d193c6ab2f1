"""The render views and the clip the picture scripts share (pvpython)."""
from paraview.simple import Clip, GetActiveViewOrCreate, GetScalarBar

# The tissues of the images in the guide's pictures: (label, name, colour), one colour each.
NESTED_SHELLS = [(1, "outer shell", (0.90, 0.62, 0.00)), (2, "middle shell", (0.34, 0.71, 0.91)),
                 (3, "core", (0.00, 0.62, 0.45))]
BRAIN = [(1, "brain", (0.85, 0.65, 0.60))]
THREE_TISSUES = [(1, "CSF", (0.30, 0.60, 0.95)), (2, "grey matter", (0.55, 0.55, 0.60)),
                 (3, "white matter", (0.95, 0.93, 0.85))]
# The New York Head's tissues as ROAST names them.
NEW_YORK_HEAD = [(1, "white matter", (0.95, 0.93, 0.85)), (2, "grey matter", (0.55, 0.55, 0.6)),
                 (3, "CSF", (0.3, 0.6, 0.95)), (4, "bone", (0.95, 0.85, 0.55)),
                 (5, "skin and soft tissue", (0.9, 0.6, 0.55)), (6, "air", (0.7, 0.9, 0.75))]


def white(view):
    """A render view on a white background without axes."""
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    return view


def white_view(size):
    """The active render view, sized, on a white background without axes."""
    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = size
    return white(view)


def middle_clip(source):
    """Whole tets (as in the paper's cross-sections) on one side of the plane x = the centre of
    the source's bounds; returns the clip, the centre and the bounds."""
    bounds = source.GetDataInformation().GetBounds()
    centre = [(bounds[2 * a] + bounds[2 * a + 1]) / 2 for a in range(3)]
    clip = Clip(Input=source)
    clip.ClipType = "Plane"
    clip.ClipType.Origin = centre
    clip.ClipType.Normal = [1, 0, 0]
    clip.Crinkleclip = 1
    return clip, centre, bounds


def tissue_colours(lut, tissues):
    """One colour per label, named in the legend: a categorical map, not a continuous bar
    running from the smallest label to the largest. tissues: (label, name, colour) triples."""
    lut.InterpretValuesAsCategories = 1
    lut.AnnotationsInitialized = 1
    lut.Annotations = [text for label, name, _ in tissues for text in (str(label), name)]
    lut.IndexedColors = [c for _, _, colour in tissues for c in colour]


def tissue_legend(lut, view, font_size=20):
    """The legend of tissue_colours' map: a swatch and the name of each tissue."""
    bar = GetScalarBar(lut, view)
    bar.Title = "tissue"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.TitleFontSize = bar.LabelFontSize = font_size
    bar.TextPosition = "Ticks left/bottom, annotations right/top"
    bar.Visibility = 1
    return bar
