"""The render views and the clip the picture scripts share (pvpython)."""
from paraview.simple import Clip, GetActiveViewOrCreate


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
