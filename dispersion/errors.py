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


def check_nu(nu):
    """Return ``nu`` if it is a symbol or a real number in (-1, 0.5); raise otherwise."""
    if not _is_number(nu):
        if getattr(nu, "is_Symbol", False):
            return nu
        if getattr(nu, "is_number", False) and getattr(nu, "is_real", False):
            if -1 < nu < 0.5:
                return nu
        raise InputError(f"nu must lie in (-1, 0.5), got {nu!r}")
    if not (math.isfinite(float(nu)) and -1 < nu < 0.5):
        raise InputError(f"nu must lie in (-1, 0.5), got {nu}")
    return nu


def check_positive_int(name: str, value, minimum: int = 1) -> int:
    """Return ``value`` as int if it is an integer >= ``minimum``; raise otherwise."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < minimum:
        raise InputError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


def check_positive(name: str, value):
    """Return ``value`` if it is a finite positive number (or a positive symbol)."""
    if getattr(value, "is_Symbol", False):
        return value
    try:
        ok = math.isfinite(float(value)) and float(value) > 0
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise InputError(f"{name} must be a finite number > 0, got {value!r}")
    return value


def check_wavenumbers(kappa):
    """``kappa`` as a non-empty 1-d float array of finite values >= 0, else :class:`InputError`."""
    import numpy as np

    kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
    if kappa.ndim != 1 or kappa.size == 0:
        raise InputError("kappa must be a non-empty 1-d array")
    if not np.all(np.isfinite(kappa)) or np.any(kappa < 0):
        raise InputError("kappa must be finite and >= 0")
    return kappa
