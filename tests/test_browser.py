"""A real browser: JupyterLab in headless Debian Chromium runs lesson 06 and moves a slider.

Playwright drives the system Chromium (never `playwright install`, which downloads a browser).
JupyterLab serves a temporary copy of the lessons so autosave never touches the repository.
"""

import shutil
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.browser

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "tools"))
import browser  # noqa: E402


def write_every_demo_notebook(path: Path) -> None:
    """A notebook that shows every registered demo, one per cell, live (``%matplotlib widget``)."""
    import nbformat

    from camlab.widgets import all_demos

    cells = [
        nbformat.v4.new_code_cell(
            "%matplotlib widget\nfrom camlab.widgets import all_demos\nDEMOS = all_demos()"
        )
    ]
    cells += [
        nbformat.v4.new_code_cell(f"DEMOS[{name!r}].builder()") for name in sorted(all_demos())
    ]
    kernel = {"name": "python3", "display_name": "Python 3 (ipykernel)", "language": "python"}
    nbformat.write(nbformat.v4.new_notebook(cells=cells, metadata={"kernelspec": kernel}), path)


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    browser.require_chromium()
    base = tmp_path_factory.mktemp("lab")
    shutil.copytree(REPO / "lessons", base / "root" / "lessons")
    write_every_demo_notebook(base / "root" / "every_demo.ipynb")
    with browser.jupyterlab(base / "root", base) as lab:
        yield lab


def test_lesson_06_runs_and_a_slider_moves_the_figure(lab):
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        context = browser.launch(p, lab["profile"])
        try:
            page = context.new_page()
            page.set_default_timeout(90_000)
            browser.run_notebook(page, lab, "lessons/06_projective_plane.ipynb")
            demo = page.locator(".camlab-demo-parallel-lines")
            demo.wait_for(state="attached")
            demo.scroll_into_view_if_needed()
            demo.locator("canvas").first.wait_for(state="visible")
            page.wait_for_function(
                "() => (document.querySelector('.camlab-demo-parallel-lines pre') || {}).textContent?.includes('l1 × l2')"
            )
            page.wait_for_function(browser.ALL_CELLS_RUN, polling=500)
            page.wait_for_timeout(1000)
            before_png, after_png, before_text, after_text = browser.click_slider(
                page, "camlab-demo-parallel-lines", 0.8
            )  # the angle slider
            # camlab.widgets' page script (camlab/_access.py): every slider handle has a name, and
            # Tab leaves a figure (ipympl's canvas would keep the focus: a keyboard trap).
            sliders = page.locator(".jp-OutputArea [role=slider]").count()
            unnamed = page.evaluate(
                "() => [...document.querySelectorAll('.jp-OutputArea [role=slider]')].filter(h => !h.getAttribute('aria-label')).length"
            )
            # a figure ipympl still draws (parallel_lines is drawn in the browser: camlab.widgets.browser)
            figure = page.locator(".jp-OutputArea .jupyter-matplotlib-canvas-div").first
            figure.focus()
            focused_before = figure.evaluate("el => el === document.activeElement")
            page.keyboard.press("Tab")
            still_in_figure = figure.evaluate("el => el === document.activeElement")
            errors = page.locator(
                ".jp-OutputArea-output[data-mime-type='application/vnd.jupyter.stderr']"
            )
            stderr = [t for t in errors.all_text_contents() if "Error" in t]
            # Each figure's bundle also carries a static PNG for readers without a kernel;
            # JupyterLab must show the live widget only, never the PNG under it.
            static_images = page.locator(
                ".jp-OutputArea-output[data-mime-type='image/png']"
            ).count()
            live_canvases = page.locator(".jp-OutputArea-output canvas").count()
        finally:
            context.close()
    assert before_text != after_text, "the slider did not reach the kernel"
    assert before_png != after_png, "the slider moved but the figure did not change"
    assert not stderr, f"lesson 06 printed errors in the browser: {stderr[:2]}"
    assert static_images == 0, (
        f"JupyterLab shows {static_images} static PNGs under the live figures"
    )
    assert live_canvases >= 6, (
        f"expected the 6 live figures of lesson 06, found {live_canvases} canvases"
    )
    assert sliders >= 10 and unnamed == 0, (
        f"{unnamed} of {sliders} slider handles have no accessible name"
    )
    assert focused_before and not still_in_figure, (
        "Tab does not leave a focused figure (a keyboard trap)"
    )


MEASURE_DEMOS = """() => [...document.querySelectorAll('[class*=camlab-demo-]')].map((demo) => {
  const out = demo.closest('.jp-OutputArea-output'), canvas = demo.querySelector('canvas');
  const [panel, figure] = demo.children, a = panel.getBoundingClientRect(), b = figure.getBoundingClientRect();
  const overlap = Math.max(0, Math.min(a.right, b.right) - Math.max(a.left, b.left))
                * Math.max(0, Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top));
  return {name: [...demo.classList].find((c) => c.startsWith('camlab-demo-')), area: out.clientWidth,
          needs: demo.scrollWidth, canvasRight: canvas ? canvas.getBoundingClientRect().right : null,
          areaRight: out.getBoundingClientRect().right, panelNeeds: panel.scrollWidth, panel: panel.clientWidth,
          overlap: overlap};
})"""


KERNEL_STATUS = (
    "() => window.jupyterapp.shell.currentWidget?.sessionContext?.session?.kernel?.status ?? 'none'"
)


def _scroll_until_drawn(page, demo, tries: int = 3) -> bool:
    """Scroll ``demo`` into view until its canvas is drawn (up to 3 x 45 s); False if it never is.

    A canvas scrolled into view while the kernel is still busy with the demos above it can stay
    unsized (0 x 0) after the kernel catches up (seen in CI under load). Each retry changes the
    window's height by 1 px, which makes ipympl ask the kernel for the frame again (the width,
    which the test measures, stays). CI twice saw one canvas stay 0 x 0 through every retry
    (`opencv_vs_opengl`, then another demo), and re-running its cell from the test did not redraw
    it either (JupyterLab's windowed notebook): the caller tolerates one such canvas, never two.
    """
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    for _ in range(tries):
        demo.scroll_into_view_if_needed()
        try:
            demo.locator("canvas").first.wait_for(state="visible", timeout=45_000)
            return True
        except PlaywrightTimeout:
            size = page.viewport_size
            page.set_viewport_size({"width": size["width"], "height": size["height"] - 1})
            page.wait_for_timeout(500)
            page.set_viewport_size(size)
    return False


def _measure_every_demo(p, lab) -> tuple[dict, list]:
    """Run every_demo.ipynb in a fresh 1400 x 1000 window with the file browser open, scroll each
    demo into view until drawn, and measure them all: ``(undrawn, measured)``.

    ``undrawn`` maps each demo whose canvas never drew to the kernel's status then. CI once saw
    every canvas after one stay undrawn, each waiting its 3 x 45 s into the timeout; the second
    already fails the check, so the scan stops there.
    """
    context = browser.launch(p, lab["profile"])  # a 1400 x 1000 window
    try:
        page = context.new_page()
        page.set_default_timeout(180_000)
        browser.run_notebook(page, lab, "every_demo.ipynb")
        page.wait_for_function(browser.ALL_CELLS_RUN, polling=500)
        if (
            page.evaluate(
                "() => document.querySelector('#jp-left-stack').getBoundingClientRect().width"
            )
            < 100
        ):
            page.evaluate("() => window.jupyterapp.commands.execute('filebrowser:activate')")
        page.wait_for_function(
            "() => document.querySelector('#jp-left-stack').getBoundingClientRect().width > 200"
        )
        undrawn = {}  # drawn only once scrolled into view
        for demo in page.locator("[class*=camlab-demo-]").all():
            if not _scroll_until_drawn(page, demo):
                classes = demo.get_attribute("class").split()
                name = next(c for c in classes if c.startswith("camlab-demo-"))
                undrawn[name] = page.evaluate(KERNEL_STATUS)
            if len(undrawn) > 1:
                break
        page.wait_for_timeout(1000)
        return undrawn, page.evaluate(MEASURE_DEMOS)
    finally:
        context.close()


@pytest.mark.long_browser
@pytest.mark.timeout(1500)  # two runs of the notebook at most (below)
def test_every_demo_fits_at_1400_px_with_the_file_browser_open(lab):
    """Nothing clipped in JupyterLab's output area at a 1400 px window with the file browser open
    (968 px): the controls and the figure sit side by side where both fit, else the figure wraps
    under the controls (demos 1100 px wide were once cut off on the right).

    Two canvases that never draw, with the kernel idle (CI, 7c5ef26b: feature-matches and
    flip-pose), are a load flake of ipympl's first frame in the browser, not a layout fault:
    the notebook then runs once more, in a fresh window, and that run is measured. Both runs'
    undrawn canvases are in the message if the second fails too.
    """
    from playwright.sync_api import sync_playwright

    from camlab.widgets import all_demos

    with sync_playwright() as p:
        undrawn, measured = _measure_every_demo(p, lab)
        first = undrawn
        if len(undrawn) > 1:
            undrawn, measured = _measure_every_demo(p, lab)
    assert len(undrawn) <= 1, (
        f"canvases never drawn (0 x 0) through every retry (kernel status): first run {first}, "
        f"second run {undrawn}"
    )
    assert len(measured) == len(all_demos())
    assert all(940 <= m["area"] <= 1000 for m in measured), (
        f"not the setting of the check: {measured[:2]}"
    )
    clipped = [
        f"{m['name']}: needs {m['needs']} px, canvas ends at {m['canvasRight']} of {m['areaRight']:.0f}, "
        f"controls need {m['panelNeeds']} of {m['panel']} px, {m['overlap']:.0f} px2 under the figure"
        for m in measured
        if m["name"] not in undrawn  # at most one, a load flake of ipympl's first frame (above)
        and (
            m["needs"] > m["area"]
            or m["canvasRight"] is None
            or m["canvasRight"] > m["areaRight"] + 1
            or m["panelNeeds"] > m["panel"] + 1
            or m["overlap"] > 0
        )
    ]
    assert not clipped, "demos clipped at 1400 px with the file browser open:\n  " + "\n  ".join(
        clipped
    )
