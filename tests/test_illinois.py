"""The shared Illinois root finder (dispersion.continuum.illinois)."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.continuum.illinois import illinois, scalar_root


SHAPES = {"line": lambda d: d, "cubic": lambda d: d * (1 + d * d),
          "tanh": np.tanh, "exp": np.expm1}


@settings(max_examples=50, deadline=None)
@given(roots=st.lists(st.floats(0.1, 100), min_size=1, max_size=20),
       shape=st.sampled_from(sorted(SHAPES)), flip=st.booleans())
def test_brackets_close_on_the_known_root(roots, shape, flip):
    # f = +-g(x - r), g increasing with a simple zero at 0, on [r/3, 2r]: the root r is known
    # exactly; every row converges to rtol (or to no float strictly inside), whichever sign
    # the left end has
    r = np.array(roots)
    sign = -1.0 if flip else 1.0

    def f(idx, x):
        return sign * SHAPES[shape](x - r[idx])

    a, b = r / 3, 2 * r
    got, lo, hi, still_open = illinois(f, a, b, f(np.arange(r.size), a), f(np.arange(r.size), b),
                                       1e-15)
    assert not still_open.any()
    assert np.all(lo <= hi)
    # the rounding of x - r and of g near 0 leaves a few ulps of r
    assert np.all(np.abs(got - r) <= 1e-15 * r + 4 * np.spacing(r))


def test_stalling_regula_falsi_is_unstuck():
    # exp(x) - 1e4 on [0, 20]: plain regula falsi keeps the left end for hundreds of steps;
    # with the Illinois halving it converges in a few dozen
    f = lambda idx, x: np.exp(x) - 1e4  # noqa: E731
    a, b = np.array([0.0]), np.array([20.0])
    got, _, _, still_open = illinois(f, a, b, f(0, a), f(0, b), 1e-15, max_iter=60)
    assert not still_open[0] and got[0] == pytest.approx(np.log(1e4), rel=1e-15)


def test_open_brackets_are_reported_not_hidden():
    # two steps cannot close [0, 20] on exp(x) - 1e4 to 1e-15: the row is reported open
    def f(idx, x):
        return np.exp(x) - 1e4

    a, b = np.array([0.0]), np.array([20.0])
    _, _, _, still_open = illinois(f, a, b, f(0, a), f(0, b), 1e-15, max_iter=2)
    assert still_open[0]


def test_scalar_root():
    assert scalar_root(lambda x: x - 0.3, 0.0, 1.0, 1e-15) == pytest.approx(0.3, rel=1e-15)
    with pytest.raises(ValueError, match="no sign change"):
        scalar_root(lambda x: x * x + 1, -1.0, 1.0, 1e-15)
