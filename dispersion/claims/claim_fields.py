"""Values of a claims entry's fields: exact numbers, rationals and expressions, checked.

Each reader takes the field's ``key`` and a ``fail(key, message)`` callback that raises the
:class:`~dispersion.errors.InputError` naming file, line, claim and field
(:func:`dispersion.claims.schema.parse_claims` supplies it). Text goes through the
whitelist reader :mod:`dispersion.claims.reader` and is never evaluated.

>>> def fail(key, message):
...     raise ValueError(f"{key}: {message}")
>>> number(0.3, "nu", fail), rational("1/2", "r", fail)
(Fraction(3, 10), 1/2)
>>> number(float("nan"), "nu", fail)
Traceback (most recent call last):
...
ValueError: nu: must be a finite number, got nan
"""
from __future__ import annotations

import math
from fractions import Fraction

import sympy

from dispersion.claims import reader
from dispersion.errors import InputError

__all__ = ["MAX_INT_BITS", "shown", "number", "rational", "expression"]

#: Largest TOML integer taken as a number (about 60 digits, as :data:`reader.MAX_DIGITS`).
MAX_INT_BITS = 200


def shown(value, limit: int = 60) -> str:
    """``repr`` of a user's value for a message: control characters escaped, length bounded."""
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 200:
        return f"an integer of {value.bit_length()} bits"
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


def number(value, key, fail, symbol=None):
    """An exact number of a value field: a TOML integer, float or string (``"1/2"``).

    Strings go through :func:`dispersion.claims.reader.read_number` (bounded digits, no
    evaluation); floats through their shortest decimal text (0.3 is 3/10); NaN, infinities,
    booleans and integers of more than :data:`MAX_INT_BITS` bits are refused. A string equal
    to the name of ``symbol`` (``"r"``) is that symbol.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        fail(key, f"must be a number (or a fraction such as '1/2'), got {shown(value)}")
    if isinstance(value, int):
        if value.bit_length() > MAX_INT_BITS:
            fail(key, f"an integer of {value.bit_length()} bits is out of range (at most "
                      f"{MAX_INT_BITS} bits)")
        return Fraction(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            fail(key, f"must be a finite number, got {value!r}")
        value = repr(value)
    elif symbol is not None and value.strip() == str(symbol):
        return symbol
    try:
        return reader.read_number(value)
    except InputError as exc:
        fail(key, f"{shown(value)} is not a number: {exc}")


def rational(value, key, fail, symbol=None):
    """:func:`number` as a sympy Rational (or ``symbol``)."""
    q = number(value, key, fail, symbol)
    return q if q is symbol else sympy.Rational(q.numerator, q.denominator)


def expression(text, key, syntax, fail):
    """A coefficient or series: text through the reader; a TOML number as an exact value."""
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return rational(text, key, fail)
    if not isinstance(text, str) or not text.strip():
        fail(key, f"must be an expression (a string), got {shown(text)}")
    try:
        return reader.read(text, syntax)
    except InputError as exc:
        what = "LaTeX" if syntax == "latex" else "sympy text"
        fail(key, f"{exc} (reading {what} {shown(text)})")
