"""Matplotlib helpers: the one place (with camlab.widgets) where plotting lives.

Helpers live in topic submodules, imported explicitly so that ``import camlab`` never
imports matplotlib: ``camlab.plotting.conventions`` (pixels and the camera frame, lesson 00),
``camlab.plotting.plane`` (the projective plane, lesson 06) and one
module per further topic (3-D camera views, optics diagrams, images side by side...).
"""
