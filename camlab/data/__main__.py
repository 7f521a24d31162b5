"""``python -m camlab.data [DIR]``: regenerate every rendered data set (see :mod:`camlab.fixtures.regenerate`).

An entry point, imported by nothing: it may reach the generators above :mod:`camlab.data`.
The command keeps its name because the bundled sets' ``truth.json`` files and manifest name it.
"""

from ..fixtures.regenerate import main

raise SystemExit(main())
