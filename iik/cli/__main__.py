"""``python -m iik.cli ...`` runs the ``iik`` command."""

import sys

from . import main

sys.exit(main())
