"""Through-thickness mode shapes of the discrete patch, and branch pairing by mode shape (MAC).

The discrete shape is the B-spline field of the control values through the thickness,
sampled at the points of the exact shapes (:mod:`dispersion.continuum.mode_shapes`). The modal
assurance criterion :math:`\\mathrm{MAC}(a, b) = (a^T b)^2 / (a^T a\\, b^T b)` pairs each exact
branch with the discrete mode it resembles most (an assignment maximising the total MAC), so an
error curve compares like with like even where the discrete spectrum orders its modes
differently.

>>> mac([1.0, 2.0], [2.0, 4.0])
1.0

References
----------
R. J. Allemang, Sound and Vibration 37 (2003) 14-23 (the modal assurance criterion).
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from dispersion.splines.bspline import SplineBasis1D, open_knot_vector
from dispersion.symbolic.plate import PlatePatch, numeric_pencil, with_nu
from dispersion.continuum.mode_shapes import SAMPLES, exact_mode_shape

__all__ = [
    "PairedBranches",
    "discrete_mode_shape",
    "discrete_modes",
    "mac",
    "pair_by_shape",
]

#: Below this MAC a pair is not trusted and the error is not reported (NaN).
MAC_MIN = 0.5


def discrete_mode_shape(patch: PlatePatch, x: np.ndarray, y=SAMPLES):
    """:math:`(U_x, U_y)` of a discrete mode (control values ``x``, length 2n) at ``y``.

    The sign of :math:`U_x` follows the exact convention :math:`u_x = i U_x` (the patch's
    real formulation carries the quarter-period lag in the sign of its ``s`` coupling), so
    MAC values compare like with like.
    """
    x = np.asarray(x, dtype=float)
    n = patch.n
    basis = _thickness_basis(patch.p, n)
    active, N = basis.evaluate(np.asarray(y, dtype=float))
    ux = np.einsum("ma,ma->m", N, x[:n][active])
    uy = np.einsum("ma,ma->m", N, x[n:][active])
    norm = np.sqrt(np.sum(ux**2 + uy**2))
    return _UX_SIGN * ux / norm, uy / norm


@functools.lru_cache(maxsize=32)
def _thickness_basis(p: int, n: int) -> SplineBasis1D:
    """The patch's basis through the thickness: n open B-splines of degree p on [-1, 1]."""
    return SplineBasis1D.from_knots(open_knot_vector(p, n - p, -1, 1))


#: u_x of the patch's real formulation is -U_x of the convention above (checked by
#: tests/test_mode_shapes.py on S0 and A0 at small kappa, where MAC -> 1).
_UX_SIGN = -1.0


def mac(a, b) -> float:
    """Modal assurance criterion of two real shape vectors, in [0, 1].

    >>> mac([1.0, 2.0], [2.0, 4.0]), mac([1.0, 0.0], [0.0, 1.0])
    (1.0, 0.0)
    """
    a, b = np.ravel(a), np.ravel(b)
    return float(np.dot(a, b) ** 2 / (np.dot(a, a) * np.dot(b, b)))


def discrete_modes(patch: PlatePatch, nu, kappa) -> tuple[np.ndarray, np.ndarray]:
    """All finite discrete modes, ascending: ``Omega (m, f)`` and control values ``(m, 2n, f)``.

    Frequencies where float round-off would blur them are recomputed in extended precision
    (as in :func:`dispersion.discretization.discrete_branches.discrete_branches`).
    """
    patch = with_nu(patch, nu)
    from dispersion.discretization.extended_pencil import refine_inaccurate
    from dispersion.discretization.pencil_frequencies import pencil_frequencies

    kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
    K, M = numeric_pencil(patch, None, kappa)
    W, X, err = pencil_frequencies(K, M, patch.massless, vectors=True, bounds=True)
    return refine_inaccurate(patch, None, kappa, W, None, error=err), X


@dataclass(frozen=True)
class PairedBranches:
    """Discrete partners of the exact branches: ``omega[label]`` and its ``mac[label]``;
    ``partner[label]``: which discrete mode (its place in ascending Omega, -1: none) it is at
    each kappa, so a change of partner shows as one (a plot breaks its line there)."""

    kappa: np.ndarray
    omega: dict[str, np.ndarray]
    mac: dict[str, np.ndarray]
    partner: dict[str, np.ndarray] | None = None

    def relative_error(self, exact) -> dict[str, np.ndarray]:
        """Signed :math:`(\\Omega^h - \\Omega)/\\Omega` per exact label (NaN where unpaired)."""
        out = {}
        for label, w in self.omega.items():
            ref = exact.omega[label]
            with np.errstate(divide="ignore", invalid="ignore"):
                out[label] = np.where(ref > 0, (w - ref) / ref, np.nan)
        return out


def pair_by_shape(patch: PlatePatch, nu, exact, y=SAMPLES,
                  mac_min: float = MAC_MIN) -> PairedBranches:
    """Pair every exact branch with a discrete mode by mode shape (see module docstring).

    At each kappa the MAC matrix between the exact modes (traced, finite) and the discrete
    modes is built and the assignment of largest total MAC chosen
    (:func:`scipy.optimize.linear_sum_assignment`); a pair with MAC below ``mac_min`` is
    dropped (NaN). ``exact`` is a :class:`dispersion.continuum.exact_branches.ExactBranches`.
    """
    patch = with_nu(patch, nu)
    from scipy.optimize import linear_sum_assignment

    kappa = exact.kappa
    W, X = discrete_modes(patch, None, kappa)
    labels = list(exact.omega)
    omega = {lab: np.full(kappa.size, np.nan) for lab in labels}
    score = {lab: np.full(kappa.size, np.nan) for lab in labels}
    partner = {lab: np.full(kappa.size, -1, dtype=int) for lab in labels}
    disc_shapes = [[np.concatenate(discrete_mode_shape(patch, X[i, :, j], y))
                    for j in range(W.shape[1])] for i in range(kappa.size)]
    for i, k in enumerate(kappa):
        present = [lab for lab in labels if np.isfinite(exact.omega[lab][i])]
        if not present:
            continue
        ex = [np.concatenate(exact_mode_shape(lab[0], float(k), float(exact.omega[lab][i]),
                                              exact.nu, y)) for lab in present]
        C = np.array([[mac(e, d) for d in disc_shapes[i]] for e in ex])
        rows, cols = linear_sum_assignment(-C)
        for r, c in zip(rows, cols):
            score[present[r]][i] = C[r, c]
            if C[r, c] >= mac_min:
                omega[present[r]][i] = W[i, c]
                partner[present[r]][i] = c
    return PairedBranches(kappa, omega, score, partner)
