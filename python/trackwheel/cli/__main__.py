"""``python -m trackwheel.cli``: the ``trackwheel`` command."""

import sys

from .main import main

sys.exit(main())
