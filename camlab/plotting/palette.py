"""Colours for figures: distinct for colour-blind readers, and contrasted enough to see.

Every pair in :data:`SERIES` stays at CIE delta-E >= 13 in normal vision and for full
protanopia, deuteranopia and tritanopia (Machado et al.'s simulation [1]_;
``tests/test_colour_vision.py`` checks it, and checks every demo's legend). The hues keep
their everyday names, so a lesson can still say "the green arrows"; they are darker or
lighter than matplotlib's ``tab:`` colours where those collapse (``tab:green`` against
``tab:red`` for deuteranopes, ``tab:orange`` against ``tab:green`` for protanopes).
Based on Paul Tol's colour schemes [2]_.

Every colour of the series reaches 3:1 against white, the contrast WCAG 2.1 asks of lines and
markers (1.4.11); all but ORANGE also reach 4.5:1, enough for text (1.4.3). ORANGE is
darker than Tol's ``#EE9944`` (2.3:1) for that reason. ``tests/test_figure_contrast.py``
measures every demo. A line or text drawn over a photograph, whose colours can be
anything, gets a white outline with :func:`halo`. Value images use perceptually uniform
colormaps (``viridis``, ``cividis``) with a colour bar instead.

References
----------
.. [1] G. M. Machado, M. M. Oliveira and L. A. F. Fernandes, 2009, "A physiologically-based model
   for simulation of color vision deficiency", *IEEE Transactions on Visualization and Computer
   Graphics* 15(6), 1291-1298.
.. [2] P. Tol, colour schemes, https://personal.sron.nl/~pault/.
"""

BLUE = "#4477AA"  # 4.7:1 on white
ORANGE = "#CC7700"  # 3.4:1: lines and markers, not text
GREEN = "#228833"  # 4.5:1
RED = "#CC3311"  # 5.2:1
PURPLE = "#AA3377"  # 6.1:1
BROWN = "#8C564B"  # 5.9:1
GREY = "#808080"  # 4.0:1: reference lines ("before", "original", construction)
DARK_ORANGE = (
    "#7A4600"  # 8.0:1: a second shade of ORANGE, for a second bundle of rays (lesson 01's cones)
)

SERIES = (BLUE, ORANGE, GREEN, RED, PURPLE, BROWN)  # for numbered things: image 0, 1, 2...
VIEWS = (
    BLUE,
    ORANGE,
    GREEN,
    BROWN,
)  # numbered views where red means a detection and purple a residual (lesson 08)

# The colours demos drew before this palette, kept under a name here so that every colour a
# figure uses is spelt in this module (``tests/test_palette.py`` fails on a raw colour
# anywhere else). Each is the very string the demos passed, so their renders stay
# byte-identical; each demo that uses one passes tests/test_colour_vision.py and
# tests/test_figure_contrast.py as it is (YELLOW, MAGENTA and TAB_CYAN fall short of 3:1 on
# white: they are drawn over images, never on a white background). A demo redesigned later
# moves to the series above.
TAB_BLUE = "tab:blue"  # #1F77B4, 4.8:1 on white
TAB_RED = "tab:red"  # #D62728, 5.0:1
TAB_GREEN = "tab:green"  # #2CA02C, 3.4:1: lines and markers, not text
TAB_CYAN = (
    "tab:cyan"  # #17BECF, 2.3:1: true matches over the grey stereo pair (lesson 11, dark halo)
)
DARK_GREEN = "darkgreen"  # #006400, 7.4:1: labels A-D of the green points (lesson 07)
YELLOW = "yellow"  # #FFFF00, 1.1:1: marks over photographs (keypoints, crops, a traced quad)
MAGENTA = "magenta"  # #FF00FF, 3.1:1: residual arrows over a grey calibration photo
BEFORE = "#BB5566"  # 4.6:1, Tol's high-contrast red: "before" in `camlab rectify`'s histogram
AFTER = "#004488"  # 9.6:1, Tol's high-contrast blue: "after" (hatched too, so not colour alone)
INDIGO = "#332288"  # 12.6:1, Tol's indigo: lesson 11's block matching, apart from its magenta
HOLE = "lime"  # #00FF00: the forward warp's holes (lesson 07): a hue neither its picture nor another mark uses
OLIVE = "#999933"  # 3.0:1, Tol's muted olive: "behind the plane" in lesson 07's parallax figure (black-edged markers)

# Neutrals (black, white and the grey levels "0.0"-"1.0") have no hue, so they cannot clash
# with a meaning or collapse for a colour-blind reader: figures may spell them directly.

AXIS_COLOURS = (RED, GREEN, BLUE)
"""The x, y and z axes of every frame, camera or world, in every lesson: red, green, blue (RGB = xyz,
as in RViz, Blender and pytransform3d): lesson 00's camera frame, the 3-D cameras and world axes
of lesson 04 (``scene3d``), its vanishing points of X, Y and Z; see docs/conventions.md."""


def halo(linewidth: float = 0.0, colour: str = "white") -> list:
    """Path effects that outline a line of ``linewidth`` points (0: a text or a marker) in ``colour``.

    Pass as ``path_effects=halo(lw)`` to a line, marker or text drawn over an image: the
    outline, 1 point each side, is the background it is seen against.

    Parameters
    ----------
    linewidth : float
        Width of the line to outline, in points; 0 for a text or a marker.
    colour : str
        The outline's colour (a neutral such as ``"white"``, or a palette colour).

    Returns
    -------
    list of matplotlib.patheffects.AbstractPathEffect
        One ``withStroke`` effect, ``linewidth + 2`` points wide, to pass as ``path_effects``.
    """
    from matplotlib import patheffects

    return [patheffects.withStroke(linewidth=linewidth + 2.0, foreground=colour)]
