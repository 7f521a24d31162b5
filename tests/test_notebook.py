"""camlab._notebook: a warning raised from a notebook cell prints without the kernel's temporary path."""

import io
import sys
import types
import warnings

import pytest

from camlab import _notebook


@pytest.mark.parametrize(
    "filename, is_cell",
    [
        ("/tmp/ipykernel_6366/3058451507.py", True),
        ("<ipython-input-3-5f2d>", True),
        ("/home/ada/camlab/stitching/pipeline.py", False),
        ("/tmp/ipykernel_helpers.py", False),
    ],
)
def test_cell_files_are_told_from_real_files(filename, is_cell):
    assert _notebook.is_cell_file(filename) is is_cell


def _shown(filename: str) -> str:
    stream = io.StringIO()
    _notebook._show_warning(
        UserWarning("stitch: left out of the panorama"),
        UserWarning,
        filename,
        2,
        stream,
        "result3 = st.stitch(turn.images)",
    )
    return stream.getvalue()


def test_a_warning_from_a_cell_prints_category_and_message_only():
    assert (
        _shown("/tmp/ipykernel_6366/3058451507.py")
        == "UserWarning: stitch: left out of the panorama\n"
    )
    real = _shown("/home/ada/script.py")
    assert (
        real.startswith("/home/ada/script.py:2: UserWarning: stitch: left out")
        and "result3" in real
    )


def test_installed_only_in_a_kernel(monkeypatch):
    before = warnings.showwarning
    assert (
        not _notebook.install_warning_format() and warnings.showwarning is before
    )  # plain pytest: no kernel
    kernel_shell = types.SimpleNamespace(kernel=object())
    monkeypatch.setitem(
        sys.modules, "IPython", types.SimpleNamespace(get_ipython=lambda: kernel_shell)
    )
    monkeypatch.setattr(warnings, "showwarning", before)  # undone after the test
    assert _notebook.install_warning_format() and _notebook.install_warning_format()
    assert warnings.showwarning is _notebook._show_warning


def test_the_page_script_shows_no_repr_where_scripts_do_not_run(monkeypatch):
    """camlab.widgets' accessibility script (camlab/_access.py): a page that runs no scripts shows nothing."""
    import IPython.display

    from camlab import _access

    shown = []
    kernel_shell = types.SimpleNamespace(kernel=object())
    monkeypatch.setattr("IPython.get_ipython", lambda: kernel_shell)
    monkeypatch.setattr(IPython.display, "display", lambda *objs, **kw: shown.append((objs, kw)))
    assert _access.install()
    (bundle,), options = shown[0]
    assert (
        options.get("raw")
        and bundle["application/javascript"] == _access.SCRIPT
        and bundle["text/plain"] == ""
    )
