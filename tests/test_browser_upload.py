"""A real browser uploads a photo: JupyterLab in headless Chromium, a file set on the upload's input.

The kernel decodes the file and its status line, rendered back in the page, names the file,
its size in bytes and its size in pixels. Same fixtures as tests/test_browser.py
(tools/browser.py): the system Chromium, a JupyterLab serving a temporary folder.
"""

import sys
from pathlib import Path

import pytest

pytestmark = [pytest.mark.browser, pytest.mark.long_browser, pytest.mark.timeout(120)]

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "tools"))
import browser  # noqa: E402


def write_upload_notebook(path: Path) -> None:
    """A notebook with one cell: a PhotoUpload, displayed."""
    import nbformat

    cell = nbformat.v4.new_code_cell(
        'from camlab.widgets.upload import PhotoUpload\nup = PhotoUpload("Your photos")\nup'
    )
    kernel = {"name": "python3", "display_name": "Python 3 (ipykernel)", "language": "python"}
    nbformat.write(nbformat.v4.new_notebook(cells=[cell], metadata={"kernelspec": kernel}), path)


def test_a_png_uploaded_in_the_browser_is_decoded_by_the_kernel(tmp_path):
    import cv2
    import numpy as np
    from playwright.sync_api import sync_playwright

    browser.require_chromium()
    root = tmp_path / "root"
    root.mkdir()
    write_upload_notebook(root / "upload.ipynb")
    photo = tmp_path / "my_board.png"
    image = np.zeros((48, 64, 3), np.uint8)
    image[::8] = 255
    cv2.imwrite(str(photo), image)
    size = photo.stat().st_size
    with browser.jupyterlab(root, tmp_path) as lab, sync_playwright() as p:
        context = browser.launch(p, lab["profile"])
        try:
            page = context.new_page()
            page.set_default_timeout(60_000)
            browser.run_notebook(page, lab, "upload.ipynb")
            control = page.locator(".camlab-photo-upload")
            control.wait_for(state="attached")
            status = control.locator(".camlab-upload-status")
            assert "No photos uploaded" in status.inner_text()
            # ipywidgets 8 keeps its <input type=file> out of the DOM and clicks it from the
            # button, so the file goes in through the chooser that click opens (playwright's
            # FileChooser.set_files is set_input_files on that very input).
            with page.expect_file_chooser() as chooser:
                control.locator("button.widget-upload").click()
            assert chooser.value.is_multiple()
            chooser.value.set_files(str(photo))
            page.wait_for_function(
                "() => document.querySelector('.camlab-upload-status')"
                ".innerText.includes('my_board.png')",
                polling=250,
            )
            text = status.inner_text()
        finally:
            context.close()
    assert "Received 1 photo" in text
    assert f"my_board.png ({size} bytes): 64 x 48 px" in text
