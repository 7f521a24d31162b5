"""Interactive demos, one module per lesson, all following the pattern in ``_base``.

In a lesson::

    %matplotlib widget
    from camlab.widgets import projective_plane as demos
    demos.parallel_lines()

``all_demos()`` imports every lesson module and returns the registry that the headless
tests and ``benchmarks/latency.py`` sweep.
"""

from __future__ import annotations

import importlib
import pkgutil

from .. import _access, _notebook
from ..plotting.static import install_canvas_formatter
from ._base import REGISTRY, Demo, DemoSpec, FigureView, build_demo, register, slider

install_canvas_formatter()  # plain figures in a lesson keep a PNG with alt text too
_access.install()  # named slider handles, Tab out of figures, focus rings (docs/accessibility.md)
_notebook.install_warning_format()  # a warning from a cell without the kernel's temporary path

__all__ = [
    "Demo",
    "DemoSpec",
    "FigureView",
    "REGISTRY",
    "all_demos",
    "build_demo",
    "register",
    "slider",
]


def all_demos() -> dict[str, DemoSpec]:
    """Import every lesson's demo module and return the registry, by demo name.

    Returns
    -------
    dict of str to DemoSpec
        Every registered demo by name: its builder, lesson and the sweep of control values
        the headless tests and ``benchmarks/latency.py`` drive it through.
    """
    for module in pkgutil.iter_modules(__path__):
        if not module.name.startswith("_"):
            importlib.import_module(f"{__name__}.{module.name}")
    return dict(REGISTRY)
