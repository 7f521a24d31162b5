"""``python -m camlab.data [DIR]``: regenerate every rendered data set (see :mod:`camlab.data.regenerate`)."""

from .regenerate import main

raise SystemExit(main())
