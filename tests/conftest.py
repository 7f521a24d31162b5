"""Shared test settings: headless figures and a fixed hypothesis profile."""
import os

os.environ.setdefault("CAMLAB_FIGURE_MODE", "agg")
os.environ.setdefault("MPLBACKEND", "Agg")

from hypothesis import settings  # noqa: E402

settings.register_profile("camlab", max_examples=60, deadline=None, derandomize=True)
settings.load_profile("camlab")
