"""Colours for things a figure tells apart by colour: distinct for colour-blind readers too.

Every pair in :data:`SERIES` stays at CIE delta-E >= 13 in normal vision and for full
protanopia, deuteranopia and tritanopia (Machado et al. 2009 simulation;
``tests/test_colour_vision.py`` checks it, and checks every demo's legend). The hues keep
their everyday names, so a lesson can still say "the green arrows"; they are darker or
lighter than matplotlib's ``tab:`` colours where those collapse (``tab:green`` against
``tab:red`` for deuteranopes, ``tab:orange`` against ``tab:green`` for protanopes).
Based on Paul Tol's colour schemes (https://personal.sron.nl/~pault/). Value images use
perceptually uniform colormaps (``viridis``, ``cividis``) instead.
"""
BLUE = "#4477AA"
ORANGE = "#EE9944"
GREEN = "#228833"
RED = "#CC3311"
PURPLE = "#AA3377"
BROWN = "#8C564B"

SERIES = (BLUE, ORANGE, GREEN, RED, PURPLE, BROWN)  # for numbered things: image 0, 1, 2...
