"""``python -m vlln.cli``: the ``vlln`` command, for subprocesses that run it by module."""

import sys

from vlln.cli import main

sys.exit(main())
