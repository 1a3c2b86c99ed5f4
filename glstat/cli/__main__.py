"""``python -m glstat.cli``: the ``glstat`` command."""

import sys

from .commands import main

sys.exit(main())
