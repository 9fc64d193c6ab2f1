"""The render view the picture scripts share (pvpython)."""
from paraview.simple import GetActiveViewOrCreate


def white_view(size):
    """The render view, sized, on a white background without axes."""
    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    return view
