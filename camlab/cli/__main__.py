"""``python -m camlab.cli``: the same command line as the ``camlab`` script (the path it had as a module)."""

import sys

from .main import main

sys.exit(main())
