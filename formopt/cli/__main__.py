"""python -m formopt.cli: the same as the formopt command."""

import sys

from . import main

sys.exit(main())
