"""Limits of claims work: the worker processes of ``dispersion verify``, and the size rules of
the reader (:mod:`dispersion.reader_limits`, re-exported here under its former name).
"""
from __future__ import annotations

from dispersion.reader_limits import *  # noqa: F401,F403 - the same objects, one place
from dispersion.reader_limits import __all__ as _READER_LIMITS

__all__ = [*_READER_LIMITS, "MAX_JOBS"]

#: Most worker processes :func:`dispersion.claims.verify.verify_claims` starts (here, in a
#: light module, so that the command line states it without sympy). A worker is a Python
#: process holding sympy and its caches: ``verify --paper`` in one process peaks at 110 MiB
#: resident, so 64 workers stay under a third of this machine's 24 GiB, and on its 2 cores
#: more workers than derivations or cores only add start-up time.
MAX_JOBS = 64
