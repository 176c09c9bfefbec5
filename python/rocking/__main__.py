"""`python -m rocking ...`: the `rocking` command."""

import sys

from .cli import main

sys.exit(main())
