"""``python -m camlab``: the same command line as the ``camlab`` script."""

import sys

from .cli import main

sys.exit(main())
