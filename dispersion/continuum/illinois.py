"""The Illinois method: bracketed roots of many real functions at once, and of one.

Regula falsi keeps a sign change inside ``[a, b]`` and steps to the secant's zero; the
Illinois modification halves the function value kept at an end that stayed put twice in a
row, which restores superlinear convergence where plain regula falsi stalls on one side.
Every bracket shrinks until its relative width is at most ``rtol``, no float lies strictly
inside it, or the function is exactly zero; the root returned is the midpoint of the final
bracket. No scipy import: the tracers of the exact branches
(:mod:`dispersion.continuum.exact_branches`), the scan at fixed frequency
(:mod:`dispersion.continuum.frequency`) and the zero-group-velocity points
(:mod:`dispersion.continuum.velocities`) share it.

>>> import numpy as np
>>> roots, *_ = illinois(lambda idx, x: x * x - np.array([2.0, 3.0])[idx],
...                      np.array([1.0, 1.0]), np.array([2.0, 2.0]),
...                      np.array([-1.0, -2.0]), np.array([2.0, 1.0]), 1e-15)
>>> bool(abs(roots[0] - 2**0.5) < 4e-16 and abs(roots[1] - 3**0.5) < 4e-16)
True

References
----------
M. Dowell, P. Jarratt, A modified regula falsi method for computing the root of an equation,
BIT 11 (1971) 168-174.
"""
from __future__ import annotations

import numpy as np

__all__ = ["illinois", "scalar_root"]


def illinois(f, a, b, fa, fb, rtol: float, max_iter: int = 200):
    """Roots of ``f(idx, x)`` on the brackets ``a < b`` with ``sign(fa) != sign(fb)``.

    ``f`` is called with the indices of the brackets still open and one point per bracket.
    Returns ``(roots, a, b, open)``: the midpoints of the final brackets, the brackets, and
    True where a bracket is still open after ``max_iter`` steps.
    """
    a, b, fa, fb = a.copy(), b.copy(), fa.copy(), fb.copy()
    side = np.zeros(a.shape, dtype=int)
    active = b > np.nextafter(a, np.inf)
    for _ in range(max_iter):
        idx = np.flatnonzero(active)
        if idx.size == 0:
            break
        A, B, FA, FB = a[idx], b[idx], fa[idx], fb[idx]
        with np.errstate(divide="ignore", invalid="ignore"):
            c = (A * FB - B * FA) / (FB - FA)
        c = np.where((c > A) & (c < B), c, 0.5 * (A + B))
        fc = f(idx, c)
        left = np.sign(fc) == np.sign(FA)   # the root lies right of c
        zero = fc == 0
        new_a, new_fa = np.where(left, c, A), np.where(left, fc, FA)
        new_b, new_fb = np.where(left, B, c), np.where(left, FB, fc)
        sd = side[idx]
        # Illinois: the end kept twice in a row has its value halved
        new_fb = np.where(left & (sd == 1), 0.5 * new_fb, new_fb)
        new_fa = np.where(~left & (sd == -1), 0.5 * new_fa, new_fa)
        side[idx] = np.where(left, 1, -1)
        new_a, new_b = np.where(zero, c, new_a), np.where(zero, c, new_b)
        a[idx], b[idx], fa[idx], fb[idx] = new_a, new_b, new_fa, new_fb
        done = (new_b - new_a <= rtol * np.abs(c)) | zero
        done |= np.nextafter(new_a, np.inf) >= new_b   # no float strictly inside
        active[idx[done]] = False
    return 0.5 * (a + b), a, b, active


def scalar_root(f, a: float, b: float, rtol: float) -> float:
    """Root of a scalar function with a sign change on ``[a, b]``, ``a < b``.

    Raises ValueError without a sign change or when the bracket stays open.

    >>> abs(scalar_root(lambda x: x**3 - 2, 1.0, 2.0, 1e-15) - 2 ** (1 / 3)) < 1e-15
    True
    """
    fa, fb = f(a), f(b)
    if not fa * fb < 0:
        raise ValueError("no sign change")
    root, _, _, still_open = illinois(lambda idx, x: np.array([f(float(x[0]))]), np.array([a]),
                                      np.array([b]), np.array([fa]), np.array([fb]), rtol)
    if still_open[0]:
        raise ValueError("did not converge")
    return float(root[0])
