"""Shared input checks of dispersion.errors: every bad value gives one InputError naming it."""
from __future__ import annotations

import fractions

import numpy as np
import pytest
import sympy

from dispersion.errors import (InputError, as_real, check_choice, check_finite,
                               check_int_in_range, check_memory, check_nu, check_positive,
                               check_positive_int, check_real_in_range, check_wavenumbers)

NON_FINITE = [float("nan"), float("inf"), -float("inf"), np.float64("nan"), sympy.nan,
              sympy.zoo, sympy.oo, sympy.I, 1 + 2j, "1", None, True, sympy.Symbol("x")]


@pytest.mark.parametrize("value", NON_FINITE)
def test_as_real_refuses_non_finite(value):
    with pytest.raises(InputError, match="^E must be a finite real number, got"):
        as_real("E", value)


@pytest.mark.parametrize("value", [0, -3, 10**400, 2.5, np.float32(1.5), np.int64(7),
                                   sympy.Rational(3, 10), sympy.sqrt(2),
                                   fractions.Fraction(10**400, 3)])
def test_as_real_accepts_finite(value):
    assert as_real("E", value) is value


@pytest.mark.parametrize("value, ok", [(0, True), (1, True), (0.5, True), (-1e-300, False),
                                       (1 + 1e-15, False), (10**400, False),
                                       (-(10**400), False), (sympy.Rational(1, 2), True),
                                       (sympy.Float(1.5), False)])
def test_check_real_in_range_is_exact(value, ok):
    if ok:
        assert check_real_in_range("gamma_s", value, 0, 1) == value
    else:
        with pytest.raises(InputError, match=r"^gamma_s must lie in \[0, 1\], got"):
            check_real_in_range("gamma_s", value, 0, 1)


def test_check_real_in_range_open_ends_and_huge_int_message():
    with pytest.raises(InputError, match=r"r must lie in \(0, inf\), got 0"):
        check_real_in_range("r", 0, 0, None, lo_open=True)
    with pytest.raises(InputError, match=r"got 1e\+400$"):
        check_real_in_range("r", 10**400, 0, 10, lo_open=True)
    with pytest.raises(InputError, match=r"got -1e\+400$"):
        check_real_in_range("r", -(10**400), 0, 10)


@pytest.mark.parametrize("value", [1.5, float("nan"), "3", True, None, 10**400, -1])
def test_check_int_in_range_refuses(value):
    with pytest.raises(InputError, match=r"^order must be an integer in \[0, 200\]"):
        check_int_in_range("order", value, 0, 200)


def test_check_int_in_range_accepts_integral_values():
    assert check_int_in_range("order", 4.0, 0, 200) == 4
    assert check_int_in_range("order", np.int16(8), 0, 200) == 8
    assert check_int_in_range("order", sympy.Integer(6), 0, 200) == 6


@pytest.mark.parametrize("value", [sympy.nan, sympy.zoo, float("nan"), 10**400, 0.5, -1, "0.3"])
def test_check_nu_refuses(value):
    with pytest.raises(InputError, match=r"^nu must .*\(-1, 0\.5\)"):
        check_nu(value)


def test_check_nu_keeps_symbols_and_exact_values():
    nu = sympy.Symbol("nu")
    assert check_nu(nu) is nu
    assert check_nu(sympy.Rational(3, 10)) == sympy.Rational(3, 10)


@pytest.mark.parametrize("value", [0, -1, 10**400 * -1, float("nan"), float("inf"), sympy.zoo,
                                   "2"])
def test_check_positive_refuses(value):
    with pytest.raises(InputError, match=r"^aspect ratio r must be a finite number > 0"):
        check_positive("aspect ratio r", value)


def test_check_positive_huge_int_is_not_an_overflow():
    assert check_positive("r", 10**400) == 10**400  # range limits are the caller's


def test_check_positive_int_maximum():
    with pytest.raises(InputError, match=r"jobs must be an integer in \[1, 64\], got 65"):
        check_positive_int("jobs", 65, maximum=64)


def test_check_finite_arrays():
    assert check_finite("kappa", np.arange(3.0)).shape == (3,)
    with pytest.raises(InputError, match="kappa must hold finite real numbers"):
        check_finite("kappa", np.array([0.0, np.nan]))


def test_check_choice():
    assert check_choice("mass", "lumped", ("lumped", "singular")) == "lumped"
    for bad in ("heavy", None, ["lumped"]):
        with pytest.raises(InputError, match="^mass must be one of lumped, singular; got"):
            check_choice("mass", bad, ("lumped", "singular"))


def test_check_memory_names_the_bound():
    assert check_memory("--count", 10, limit=100) == 10
    with pytest.raises(InputError, match=r"^--count would need about 1\.0 GiB, more than the "
                                         r"bound of 0\.5 GiB"):
        check_memory("--count", 2**30, limit=2**29)


@pytest.mark.parametrize("kappa", [[], [np.nan], [-1.0], [[1.0, 2.0]], ["a"], [10**400]])
def test_check_wavenumbers_refuses(kappa):
    with pytest.raises(InputError, match="^kappa must"):
        check_wavenumbers(kappa)
