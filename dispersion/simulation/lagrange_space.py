"""C0 Lagrange elements in the nodal Gauss-Lobatto-Legendre basis: the spectral-element space.

For a rule of the registry whose ``basis`` is ``"lagrange"`` (the spectral-element comparator)
the strip is discretized by continuous piecewise polynomials of degree p. Their nodal basis at
the p + 1 Gauss-Lobatto-Legendre (GLL) points of each element is the one in which the GLL
quadrature mass is diagonal (the spectral element method), so the explicit step divides.
The space is the same as the C0 B-spline (Bernstein) space of the registry's rule; the two
bases are congruent, so the frequencies agree (tested).

Element matrices use Gauss-Legendre quadrature with p + 1 points (exact for the degree-2p
products); the lumped mass is the GLL quadrature, :math:`M_{kk} = \\sum_e w_k h_e / 2`.

>>> space = NodalSpace1D(2, 3, 0.0, 3.0)
>>> space.n, round(float(space.lumped().sum()), 12)      # 2 * 3 + 1 nodes, length 3
(7, 3.0)

References
----------
Y. Maday, A. T. Patera, in State-of-the-Art Surveys on Computational Mechanics, ASME (1989)
71-143. M. Ainsworth, H. A. Wajid, SIAM J. Numer. Anal. 47 (2009) 3910-3937. M. Abramowitz,
I. Stegun, 25.4.32 (Lobatto quadrature).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from dispersion.errors import InputError, check_positive_int

__all__ = ["NodalSpace1D"]


@dataclass(frozen=True)
class NodalSpace1D:
    """Degree ``p`` C0 Lagrange elements, ``n_elements`` equal ones on ``[a, b]``, GLL nodes."""

    p: int
    n_elements: int
    a: float
    b: float

    def __post_init__(self):
        check_positive_int("degree p", self.p)
        check_positive_int("elements", self.n_elements)
        if not self.b > self.a:
            raise InputError(f"interval must have b > a, got [{self.a}, {self.b}]")

    @property
    def n(self) -> int:
        return self.n_elements * self.p + 1

    @cached_property
    def _reference(self):
        from dispersion.splines.spline_mass import lobatto_rule

        nodes, weights = lobatto_rule(self.p + 1)
        V = np.vander(nodes, self.p + 1, increasing=True)  # V[i, j] = x_i^j
        C = np.linalg.inv(V)  # column k: monomial coefficients of the k-th Lagrange polynomial
        return nodes, weights, C

    def _shape(self, xi: np.ndarray, deriv: int) -> np.ndarray:
        """Lagrange polynomials (or first derivatives) at reference points: (m, p + 1)."""
        _, _, C = self._reference
        powers = np.arange(self.p + 1)
        if deriv == 0:
            P = xi[:, None] ** powers
        else:
            P = np.where(powers > 0, powers * xi[:, None] ** np.maximum(powers - 1, 0), 0.0)
        return P @ C

    @property
    def h(self) -> float:
        return (self.b - self.a) / self.n_elements

    def _active(self, e: np.ndarray) -> np.ndarray:
        return e[:, None] * self.p + np.arange(self.p + 1)

    def grams(self) -> dict[str, sp.csr_matrix]:
        """``{"00", "01", "10", "11"}``: :math:`\\int N^{(a)}_i N^{(b)}_j dx` (CSR)."""
        g, w = np.polynomial.legendre.leggauss(self.p + 1)
        L = {0: self._shape(g, 0), 1: self._shape(g, 1) * 2 / self.h}
        ne, q = self.n_elements, self.p + 1
        act = self._active(np.arange(ne))
        rows = np.repeat(act, q, axis=1).ravel()
        cols = np.tile(act, (1, q)).ravel()
        out = {}
        for key in ("00", "01", "10", "11"):
            A, B = L[int(key[0])], L[int(key[1])]
            Me = np.einsum("g,gi,gj->ij", w * self.h / 2, A, B)
            out[key] = sp.csr_matrix((np.tile(Me.ravel(), ne), (rows, cols)), shape=(self.n,) * 2)
        return out

    def lumped(self) -> sp.csr_matrix:
        """The GLL quadrature mass: diagonal in the nodal basis."""
        _, w, _ = self._reference
        d = np.zeros(self.n)
        np.add.at(d, self._active(np.arange(self.n_elements)).ravel(),
                  np.tile(w * self.h / 2, self.n_elements))
        return sp.diags(d).tocsr()

    def evaluate(self, x) -> tuple[np.ndarray, np.ndarray]:
        """``(active (m, p + 1), values (m, p + 1))`` of the basis at the points ``x``."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        e = np.minimum(((x - self.a) / self.h).astype(int), self.n_elements - 1)
        xi = 2 * (x - self.a - e * self.h) / self.h - 1
        return self._active(e), self._shape(xi, 0)
