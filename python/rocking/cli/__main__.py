"""`python -m rocking.cli ...`: the `rocking` command."""

import sys

from . import main

sys.exit(main())
