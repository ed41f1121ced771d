"""``python -m uwml.cli``: the ``uwml`` command line."""

import sys

from . import main

sys.exit(main())
