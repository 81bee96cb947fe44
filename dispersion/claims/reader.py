"""The expression reader of claims files: :mod:`dispersion.reader`, under its former name.

The whitelist reader serves every road by which text of strangers enters the toolkit (claims
files, number options, a report folder's JSON, API strings), so it lives below every wing, in
:mod:`dispersion.reader`; this name keeps working for the claims and for older code.

>>> from dispersion import reader as base
>>> read is base.read and read_number is base.read_number
True
"""
from __future__ import annotations

from dispersion.reader import *  # noqa: F401,F403 - the same objects, one place
from dispersion.reader import __all__  # noqa: F401
