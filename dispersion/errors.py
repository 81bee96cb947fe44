"""Exception and warning types raised by the toolkit, with the shared input checks.

Every check names the parameter and its valid range, so a user (or the CLI,
which prints the message on one line) knows what to change.

>>> check_nu(0.7)
Traceback (most recent call last):
...
dispersion.errors.InputError: nu must lie in (-1, 0.5), got 0.7
"""
from __future__ import annotations

import math
import numbers

__all__ = [
    "DispersionError",
    "InputError",
    "ConvergenceError",
    "IndefiniteMassWarning",
    "check_nu",
    "check_positive_int",
    "check_positive",
    "check_wavenumbers",
    "as_real",
    "check_finite",
    "check_real_in_range",
    "check_int_in_range",
    "check_choice",
    "did_you_mean",
    "check_memory",
    "physical_memory",
]


class DispersionError(Exception):
    """Base class of every error the toolkit raises on purpose."""


class InputError(DispersionError, ValueError):
    """A parameter lies outside its valid range; the message names both."""


class ConvergenceError(DispersionError, RuntimeError):
    """An iterative method (Newton, root tracing) did not reach its tolerance."""


class IndefiniteMassWarning(UserWarning):
    """A mass matrix the user asked for explicitly is not positive semi-definite."""


def _is_number(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _interval(lo, hi, lo_open: bool, hi_open: bool) -> str:
    left = "(" if lo_open or lo is None else "["
    right = ")" if hi_open or hi is None else "]"
    return f"{left}{'-inf' if lo is None else lo}, {'inf' if hi is None else hi}{right}"


def as_real(name: str, value, valid: str = "a finite real number"):
    """``value`` if it is a finite real number (int, float, numpy or sympy number), else raise.

    Python ints are kept exact (``10**400`` is a valid int, compared without overflow); NaN,
    infinities, ``sympy.nan``/``zoo``, complex numbers, symbols, strings and bools raise an
    :class:`InputError` naming ``name`` and ``valid``.

    >>> as_real("E", float("nan"), "a finite number > 0")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: E must be a finite number > 0, got nan
    """
    bad = InputError(f"{name} must be {valid}, got {value!r}")
    if isinstance(value, bool):
        raise bad
    if isinstance(value, numbers.Integral):
        return value
    if isinstance(value, numbers.Real):
        try:
            ok = math.isfinite(value)
        except (OverflowError, TypeError, ValueError):  # a huge Fraction
            ok = isinstance(value, numbers.Rational)
        if not ok:
            raise bad
        return value
    if getattr(value, "is_number", False):  # sympy: Rational, Float, sqrt(2); not nan, zoo, I
        if value.is_real is True and value.is_finite is True:
            return value
    raise bad


def check_finite(name: str, value):
    """Return ``value`` if it is a finite real number (see :func:`as_real`); raise otherwise.

    An array is accepted when every entry is finite and real.

    >>> check_finite("gamma_s", 0.5)
    0.5
    """
    if hasattr(value, "shape") and getattr(value, "ndim", 0) > 0:
        import numpy as np

        try:
            arr = np.asarray(value, dtype=float)
        except (TypeError, ValueError, OverflowError):
            raise InputError(f"{name} must hold finite real numbers") from None
        if not np.all(np.isfinite(arr)):
            raise InputError(f"{name} must hold finite real numbers, found NaN or inf")
        return value
    return as_real(name, value)


def check_real_in_range(name: str, value, lo=None, hi=None, *, lo_open: bool = False,
                        hi_open: bool = False):
    """Return ``value`` if it is a finite real number in the interval; raise otherwise.

    ``lo``/``hi`` None mean unbounded; ``lo_open``/``hi_open`` exclude the end point. The
    comparison is exact for ints and sympy numbers (no float overflow).

    >>> check_real_in_range("gamma_s", 2, 0, 1)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: gamma_s must lie in [0, 1], got 2
    >>> check_real_in_range("r", 10**400, 0, 1e6, lo_open=True)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: r must lie in (0, 1000000.0], got 1e+400
    """
    span = _interval(lo, hi, lo_open, hi_open)
    value = as_real(name, value, f"a finite real number in {span}")
    below = lo is not None and (value <= lo if lo_open else value < lo)
    above = hi is not None and (value >= hi if hi_open else value > hi)
    if bool(below) or bool(above):
        shown = value
        if isinstance(value, numbers.Integral) and abs(value) > 10**15:
            digits = str(abs(int(value)))
            shown = f"{'-' if value < 0 else ''}{digits[0]}e+{len(digits) - 1}"
        raise InputError(f"{name} must lie in {span}, got {shown}")
    return value


def check_int_in_range(name: str, value, lo: int | None = None, hi: int | None = None) -> int:
    """Return ``value`` as int if it is an integer in [lo, hi]; raise otherwise.

    Integral floats (``3.0``) and numpy integers are accepted; bools, ``3.5``, NaN are not.

    >>> check_int_in_range("order", 100000, 2, 200)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: order must be an integer in [2, 200], got 100000
    """
    span = f"[{'-inf' if lo is None else lo}, {'inf' if hi is None else hi}]"
    bad = InputError(f"{name} must be an integer in {span}, got {value!r}")
    if isinstance(value, bool):
        raise bad
    if not isinstance(value, numbers.Integral):
        if getattr(value, "is_Integer", False):
            value = int(value)
        elif isinstance(value, float) and math.isfinite(value) and value.is_integer():
            value = int(value)
        else:
            raise bad
    value = int(value)
    if (lo is not None and value < lo) or (hi is not None and value > hi):
        raise InputError(f"{name} must be an integer in {span}, got {value}")
    return value


def did_you_mean(word, valid) -> str:
    """``; did you mean 'x'?`` for the valid name nearest to ``word`` (any letter case), or
    nothing when none is near.

    >>> did_you_mean("singlar", ("consistent", "singular"))
    "; did you mean 'singular'?"
    >>> did_you_mean("zzz", ("consistent", "singular"))
    ''
    """
    import difflib

    lower = {str(v).lower(): str(v) for v in valid}
    near = difflib.get_close_matches(str(word).strip().lower(), list(lower), n=1, cutoff=0.6)
    return f"; did you mean {lower[near[0]]!r}?" if near else ""


def check_choice(name: str, value, choices) -> str:
    """Return ``value`` if it is one of ``choices``; raise naming them otherwise.

    >>> check_choice("mass", "heavy", ("consistent", "lumped"))
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: mass must be one of consistent, lumped; got 'heavy'
    """
    try:
        ok = value in tuple(choices)
    except TypeError:
        ok = False
    if not ok or not isinstance(value, str):
        raise InputError(f"{name} must be one of {', '.join(map(str, choices))}; got {value!r}"
                         f"{did_you_mean(value, choices) if isinstance(value, str) else ''}")
    return value


def physical_memory() -> int:
    """Bytes of physical memory of this machine (24 GiB assumed where it cannot be read)."""
    import os

    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):  # pragma: no cover - not POSIX
        return 24 * 2**30


def check_memory(what: str, nbytes, limit: int | None = None) -> int:
    """Refuse, up front, work whose estimated memory ``nbytes`` exceeds ``limit``.

    ``limit`` defaults to half the physical memory. ``what`` names the options that set the
    size, so the message tells the user what to lower.

    >>> check_memory("--count 100000000 with --omega-max 8", 3 * 2**40, limit=2**34)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --count 100000000 with --omega-max 8 would need about 3072.0 GiB, more than the bound of 16.0 GiB (lower it)
    """
    limit = physical_memory() // 2 if limit is None else limit
    if nbytes > limit:
        raise InputError(f"{what} would need about {nbytes / 2**30:.1f} GiB, more than the bound "
                         f"of {limit / 2**30:.1f} GiB (lower it)")
    return int(nbytes)


def check_nu(nu):
    """Return ``nu`` if it is a symbol or a real number in (-1, 0.5); raise otherwise."""
    if getattr(nu, "is_Symbol", False):
        return nu
    return check_real_in_range("nu", nu, -1, 0.5, lo_open=True, hi_open=True)


def check_positive_int(name: str, value, minimum: int = 1, maximum: int | None = None) -> int:
    """Return ``value`` as int if it is an integer >= ``minimum`` (and <= ``maximum``)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < minimum \
            or (maximum is not None and value > maximum):
        span = f">= {minimum}" if maximum is None else f"in [{minimum}, {maximum}]"
        raise InputError(f"{name} must be an integer {span}, got {value!r}")
    return int(value)


def check_positive(name: str, value):
    """Return ``value`` if it is a finite positive number (or a positive symbol)."""
    if getattr(value, "is_Symbol", False):
        return value
    value = as_real(name, value, "a finite number > 0")
    if not value > 0:
        raise InputError(f"{name} must be a finite number > 0, got {value!r}")
    return value


def check_wavenumbers(kappa):
    """``kappa`` as a non-empty 1-d float array of finite values >= 0, else :class:`InputError`."""
    import numpy as np

    try:
        kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
    except (TypeError, ValueError, OverflowError):
        raise InputError("kappa must be a non-empty 1-d array of finite numbers >= 0") from None
    if kappa.ndim != 1 or kappa.size == 0:
        raise InputError("kappa must be a non-empty 1-d array")
    if not np.all(np.isfinite(kappa)) or np.any(kappa < 0):
        raise InputError("kappa must be finite and >= 0")
    return kappa
