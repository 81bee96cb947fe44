"""``python -m dispersion`` runs the command line."""
import sys

from dispersion.cli import main

sys.exit(main())
