"""Keyboard and screen-reader fixes for the widget libraries, sent to the page by ``import camlab.widgets``.

Two faults of the libraries the demos are drawn with, mended by a small script in the page
(``tests/test_browser.py`` checks them in JupyterLab, ``tests/test_present.py`` in the
lecture view, with axe-core; see ``docs/accessibility.md``):

* ipywidgets draws sliders with noUiSlider, whose handle (``role="slider"``) has no name of
  its own: screen readers announce just a number, and axe-core reports
  ``aria-input-field-name``. The script names each handle after its widget's label.
* ipympl's figure takes keyboard focus and swallows every key, Tab included, so a keyboard
  user who tabs into a figure cannot leave it (a keyboard trap, WCAG 2.1.2). The script lets
  Tab and Shift+Tab move on; the other keys still reach matplotlib.

It also draws a clear focus ring on controls and figures (the widgets only tint a focused
slider handle, as on hover).
"""

from __future__ import annotations

SCRIPT = """(function () {
  if (window.camlabAccess) { return; }
  window.camlabAccess = true;
  // Tab leaves a figure: stop the key before ipympl's canvas handler swallows it.
  document.addEventListener('keydown', function (event) {
    if (event.key === 'Tab' && event.target.classList.contains('jupyter-matplotlib-canvas-div')) {
      event.stopImmediatePropagation();
    }
  }, true);
  // A focus ring that shows on every control and figure.
  var style = document.createElement('style');
  style.textContent = '.jupyter-widgets :focus-visible, .jupyter-matplotlib-canvas-div:focus-visible ' +
                      '{ outline: 3px solid #1a4f8b; outline-offset: 2px; }';
  document.head.appendChild(style);
  // Name each slider handle after its widget's label, now and for every widget drawn later.
  function nameHandles() {
    document.querySelectorAll('.widget-slider .noUi-handle:not([aria-label])').forEach(function (handle) {
      var label = handle.closest('.widget-slider').querySelector('.widget-label');
      var text = label ? label.textContent.trim() : '';
      if (text) { handle.setAttribute('aria-label', text); }
    });
  }
  nameHandles();
  new MutationObserver(nameHandles).observe(document.body, {childList: true, subtree: true});
})();
"""


def install() -> bool:
    """In an IPython kernel, send :data:`SCRIPT` to the page (once per page); returns whether it did."""
    try:
        from IPython import get_ipython
        from IPython.display import display
    except ImportError:  # pragma: no cover - IPython comes with ipywidgets
        return False
    shell = get_ipython()
    if shell is None or getattr(shell, "kernel", None) is None:
        return False
    display(script_bundle(), raw=True)
    return True


def script_bundle() -> dict[str, str]:
    """The display bundle of :data:`SCRIPT`: the script, and an empty text for pages that run no scripts.

    ``IPython.display.Javascript`` also carries the text ``<IPython.core.display.Javascript
    object>``, which GitHub, an untrusted notebook or a PDF shows in place of the script.
    """
    return {"application/javascript": SCRIPT, "text/plain": ""}
