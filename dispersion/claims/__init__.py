"""Claims files: what a manuscript prints about a dispersion branch, checked against the derivation.

The format and the public functions are those of :mod:`dispersion.claims.claims`; the errata
of the paper are in :mod:`dispersion.claims.errata`.
"""
from __future__ import annotations

from dispersion.claims.claims import *  # noqa: F401,F403
from dispersion.claims.claims import __all__  # noqa: F401
