"""Packaging promises: a light import and lazy topic modules."""
import subprocess
import sys

import pytest

import camlab


def test_import_camlab_is_light():
    code = ("import sys, camlab; heavy = [m for m in ('matplotlib', 'ipywidgets', 'cv2', 'scipy') "
            "if m in sys.modules]; print(','.join(heavy))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", f"import camlab pulled in {out.stdout.strip()}"


def test_submodules_load_lazily_and_unknown_names_fail_clearly():
    assert camlab.projective.join is camlab.join
    with pytest.raises(AttributeError, match="no attribute 'nonexistent'"):
        camlab.nonexistent  # noqa: B018


def test_errors_are_value_errors():
    assert issubclass(camlab.CamlabInputError, ValueError)
    assert issubclass(camlab.DegenerateError, camlab.CamlabInputError)
