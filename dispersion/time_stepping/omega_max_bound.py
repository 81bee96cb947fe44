"""A proven upper bound on the largest frequency of a Bloch patch over its zone (ball arithmetic).

The claim :math:`\\Omega(\\theta) \\le \\bar\\Omega` for every branch and every phase
:math:`\\theta \\in [0, \\pi]` (the spectrum is even in theta) holds if and only if the
condensed matrix :math:`\\hat D = \\bar\\Omega^2 m_x M_{0,kk} - \\hat K` is positive definite
for every theta. Massless DOFs (singular rules) are *not* condensed in ball arithmetic (a
ball inverse of :math:`K_{mm}` widens fast): with them ordered first,

.. math::

    D = \\bar\\Omega^2 m_x(\\theta) M_0 - K(\\theta)
      = \\begin{pmatrix} -K_{mm} & -K_{mk} \\\\ -K_{km} & \\bar\\Omega^2 m_x M_{kk} - K_{kk}
        \\end{pmatrix},

and by Haynsworth's inertia additivity :math:`\\hat D` (the Schur complement of
:math:`-K_{mm}`) is positive definite exactly when :math:`D` has ``len(massless)``
negative and the rest positive eigenvalues. Every entry of D is a trigonometric polynomial
in theta, so on a cell :math:`|\\theta - c| \\le w` Taylor's theorem gives

.. math::

    D(\\theta) \\in \\sum_{k < T} \\frac{t^k}{k!} D^{(k)}(c)
      + \\frac{[-w, w]^T}{T!} D^{(T)}([c - w, c + w]), \\qquad t \\in [-w, w],

each term taken in the frame of the float :math:`LDL^T` factor of :math:`D(c)`:
:math:`X = |\\Delta|^{-1/2} L^{-1}` (unit triangular L: X is nonsingular, so the
congruence :math:`X D X^T \\approx \\operatorname{diag}(\\pm 1)` keeps the inertia,
Sylvester). The point terms :math:`X D^{(k)}(c) X^T` keep their structure; only the
remainder carries the cell's ball, and it is of order :math:`w^T`. An interval
:math:`LDL^T` of the sum with every pivot of certain sign proves the inertia for every
matrix in the enclosure (Rump 2006), so for every theta of the cell. Failing cells are
bisected.

>>> from dispersion.symbolic.plate import plate_patch
>>> from dispersion.time_stepping.timestep import patch_omega_max
>>> patch = plate_patch(mass="lumped", nu=0.3)
>>> w = patch_omega_max(patch, 0.3)[0]
>>> w <= certified_omega_max(patch, 0.3, w) <= 1.001 * w
True

References
----------
S. M. Rump, "Verification of positive definiteness", BIT 46 (2006) 433-452. E. V.
Haynsworth, "Determination of the inertia of a partitioned Hermitian matrix", Linear Algebra
Appl. 1 (1968) 73-81. R. E. Moore, R. B. Kearfott, M. J. Cloud, *Introduction to interval
analysis*, SIAM 2009, ch. 6 (Taylor forms).
"""
from __future__ import annotations

import math

import numpy as np
import sympy

from dispersion.errors import ConvergenceError, InputError, check_positive, check_positive_int

__all__ = ["TAYLOR_ORDER", "certified_omega_max"]

#: Order T of the Taylor form of each cell: the remainder, the only term that carries the
#: cell's ball, is of order w^T. Rule: T = 3, the smallest order with which the proof closes
#: for p = 8 (measured: T = 1 does not close in 20000 cells at p = 8).
TAYLOR_ORDER = 3
#: Working precision of the balls, in bits.
PRECISION = 128


def certified_omega_max(patch, nu, omega: float, rtol: float = 1e-3, max_cells: int = 20000
                        ) -> float:
    """A proven upper bound :math:`\\bar\\Omega = (1 + rtol)\\,\\Omega` on the largest frequency.

    The moduli of the patch's law are taken exactly
    (:meth:`~dispersion.materials.elastic_law.ElasticLaw.rational_moduli`: nu by its shortest
    decimal).
    Raises :class:`~dispersion.errors.ConvergenceError` when the proof does not close within
    ``max_cells`` cells or on a cell narrower than 1e-12: the message says that the proof did
    not close and that the bound is *not known to be false*; only where a vector
    :math:`x` with :math:`x^T \\hat D x < 0` is proven at a phase (a frequency above the bound
    there, Rayleigh quotient) does it say that the bound is false.
    """
    from dispersion.symbolic.plate import with_nu

    patch = with_nu(patch, nu)
    import flint

    if patch.model != "bloch" or isinstance(patch.r, sympy.Symbol):
        raise InputError("certification needs a Bloch patch with a numeric aspect ratio r")
    check_positive("rtol", rtol)
    max_cells = check_positive_int("max_cells", max_cells)
    old = flint.ctx.prec
    flint.ctx.prec = PRECISION
    try:
        pencil = _BallPencil(patch, (float(omega) * (1 + float(rtol))))
        top = float(omega) * (1 + float(rtol))
        cells, count = [(0.0, math.pi + 1e-12)], 0
        while cells:
            lo, hi = cells.pop()
            count += 1
            if count > max_cells:
                raise ConvergenceError(
                    f"the proof that Omega <= {top:.12g} did not close: {max_cells} cells of "
                    f"the zone were not enough (last near theta = {lo:.9g}); the bound is not "
                    "known to be false")
            if pencil.proves(lo, hi):
                continue
            if hi - lo < 1e-12:
                if pencil.refutes(lo) or pencil.refutes(hi):
                    raise ConvergenceError(f"Omega <= {top:.12g} is false: a frequency above "
                                           f"it at theta = {lo:.9g} (proven)")
                raise ConvergenceError(
                    f"the proof that Omega <= {top:.12g} did not close near theta = {lo:.9g} "
                    f"(interval matrices too wide at {PRECISION} bits); the bound is not known "
                    "to be false")
            mid = (lo + hi) / 2
            cells += [(lo, mid), (mid, hi)]
        return top
    finally:
        flint.ctx.prec = old


class _BallPencil:
    """:math:`D^{(k)}(\\theta)` of one patch and bound as flint.arb_mat, massless DOFs first."""

    def __init__(self, patch, bound: float):
        import flint

        from dispersion.symbolic.plate import mass_block, stiffness_terms, x_coefficients

        from dispersion.reader import rational

        def q(v):
            v = rational("modulus", v)
            return flint.arb(int(v.p)) / int(v.q)

        n2 = 2 * patch.n
        self.massless = len(patch.massless)
        order = list(patch.massless) + [i for i in range(n2) if i not in patch.massless]

        def arb_mat(B):
            return flint.arb_mat([[q(B[i, j]) for j in order] for i in order])

        lam = {k: q(v) for k, v in patch.law.rational_moduli().items()}
        self.terms = [(lam[m], f, arb_mat(B)) for m, f, B in stiffness_terms(patch)]
        self.M0 = arb_mat(mass_block(patch))
        self.upper = flint.arb(bound) ** 2
        c = x_coefficients(patch)  # Petrov-Galerkin rules: times their x-factor
        r = q(patch.r)
        self.cos_sums = {"m": ([(L, q(v)) for L, v in c["00"].items()], 1),
                         "d": ([(L, q(v)) for L, v in c["11"].items()], 1 / r**2),
                         "mx": ([(L, q(v)) for L, v in patch.x_mass], 1)}
        self.sin_sum = ([(L, q(v)) for L, v in c["10"].items() if L > 0], -2 / r)
        self.n2 = n2

    def _x(self, th, k: int) -> dict:
        """k-th theta-derivatives of m, s, d, m_x at th:
        :math:`(\\cos L\\theta)^{(k)} = L^k \\cos(L\\theta + k\\pi/2)`."""
        import flint

        shift = k * flint.arb.pi() / 2
        out = {}
        for name, (items, scale) in self.cos_sums.items():
            out[name] = sum((v * L**k * (L * th + shift).cos() for L, v in items),
                            flint.arb(0)) * scale
        items, scale = self.sin_sum
        out["s"] = sum((v * L**k * (L * th + shift).sin() for L, v in items),
                       flint.arb(0)) * scale
        return out

    def derivative(self, th, k: int):
        """:math:`D^{(k)}(\\theta) = \\bar\\Omega^2 m_x^{(k)} M_0 - K^{(k)}`."""
        import flint

        x = self._x(th, k)
        D = self.M0 * (self.upper * x["mx"])
        for cf, f, B in self.terms:
            D -= B * (cf * x[f])
        return D if isinstance(D, flint.arb_mat) else flint.arb_mat(D)

    def _frame(self, D):
        """``X`` (arb_mat of exact floats) with :math:`X D X^T \\approx \\operatorname{diag}(\\pm
        1)`, from the unpivoted float :math:`LDL^T` of D's midpoint; None if a pivot is zero
        or of the wrong sign."""
        import flint
        import scipy.linalg

        A = _midpoint(D)
        n = A.shape[0]
        L = np.eye(n)
        d = np.zeros(n)
        for k in range(n):   # unpivoted LDL^T (massless first: -K_mm, then the complement)
            d[k] = A[k, k] - (L[k, :k] ** 2) @ d[:k]
            if not (d[k] < 0 if k < self.massless else d[k] > 0):
                return None
            L[k + 1:, k] = (A[k + 1:, k] - (L[k + 1:, :k] * L[k, :k]) @ d[:k]) / d[k]
        Li = scipy.linalg.solve_triangular(L, np.eye(n), lower=True, unit_diagonal=True)
        X = Li / np.sqrt(np.abs(d))[:, None]
        if not np.all(np.isfinite(X)):
            return None
        return flint.arb_mat(X.tolist())

    def proves(self, lo: float, hi: float) -> bool:
        """True if D has the inertia of a true bound for every theta in [lo, hi]."""
        import flint

        centre, half = (lo + hi) / 2, (hi - lo) / 2
        X = self._frame(self.derivative(flint.arb(centre), 0))
        if X is None:
            return False
        Xt = X.transpose()
        C = X * self.derivative(flint.arb(centre), 0) * Xt
        fact = 1
        for k in range(1, TAYLOR_ORDER):
            fact *= k
            C += (X * self.derivative(flint.arb(centre), k) * Xt) * (_power(half, k) / fact)
        fact *= TAYLOR_ORDER
        C += (X * self.derivative(flint.arb(centre, half), TAYLOR_ORDER) * Xt) \
            * (_power(half, TAYLOR_ORDER) / fact)
        return _interval_inertia(C, self.massless)

    def refutes(self, theta: float) -> bool:
        """A proven :math:`y^T \\hat D y < 0` at the phase theta: the bound is false there.

        :math:`\\hat D = D_{kk} - D_{km} D_{mm}^{-1} D_{mk}` in balls at the point theta (its
        radius is rounding only), y the float eigenvector of its smallest eigenvalue; by the
        Rayleigh quotient some frequency then exceeds the bound.
        """
        import flint

        D = self.derivative(flint.arb(theta), 0)
        m, n = self.massless, self.n2
        if m:
            rows = [[D[i, j] for j in range(n)] for i in range(n)]
            Dmm = flint.arb_mat([r[:m] for r in rows[:m]])
            Dmk = flint.arb_mat([r[m:] for r in rows[:m]])
            Dkk = flint.arb_mat([r[m:] for r in rows[m:]])
            try:
                D = Dkk - Dmk.transpose() * Dmm.solve(Dmk)
            except (ValueError, ZeroDivisionError):
                return False
        y = np.linalg.eigh(_midpoint(D))[1][:, 0]
        yb = flint.arb_mat([[float(v)] for v in y])
        return bool((yb.transpose() * D * yb)[0, 0] < 0)


def _power(half: float, k: int):
    """The ball of :math:`t^k` for :math:`|t| \\le` ``half``: :math:`[-h^k, h^k]` for odd k,
    :math:`[0, h^k]` for even k (by products: flint's power of a ball holding 0 is NaN)."""
    import flint

    hk = flint.arb(1)
    for _ in range(k):
        hk *= flint.arb(half)
    return hk * (flint.arb(0, 1) if k % 2 else flint.arb(0.5, 0.5))


def _midpoint(D) -> np.ndarray:
    return np.array([[float(D[i, j].mid()) for j in range(D.ncols())]
                     for i in range(D.nrows())])


def _interval_inertia(C, negative: int) -> bool:
    """True if the interval :math:`LDL^T` of the symmetric ball matrix C (lower triangle
    used, no pivoting) succeeds with the first ``negative`` pivots certainly negative and the
    rest certainly positive: then every symmetric matrix in C has that inertia."""
    import flint

    n = C.nrows()
    L = [[None] * n for _ in range(n)]
    d = [None] * n
    zero = flint.arb(0)
    for k in range(n):
        # products, not x ** 2: flint's power of a ball that holds 0 is NaN (through its log)
        piv = C[k, k] - sum((L[k][j] * L[k][j] * d[j] for j in range(k)), zero)
        if not (piv < 0 if k < negative else piv > 0):
            return False
        d[k] = piv
        for i in range(k + 1, n):
            L[i][k] = (C[i, k] - sum((L[i][j] * L[k][j] * d[j] for j in range(k)), zero)) / piv
    return True
