"""`python -m egosim` is the `egosim` command."""

import sys

from .cli import main

sys.exit(main())
