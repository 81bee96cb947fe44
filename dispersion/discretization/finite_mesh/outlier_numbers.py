"""Outliers as numbers: how many, how high, where, and where they go as N grows.

For a finite patch and the lattice of its cell (:mod:`.lattice_reference`, largest frequency
:math:`\\omega_\\ell`):

* ``count``: the frequencies of the mesh above :math:`\\omega_\\ell (1 + 10^{-9})`;
* ``ratio``: :math:`\\omega_{max}(\\text{mesh}) / \\omega_\\ell` (the lattice's step over the
  mesh's);
* where the top mode lives: the share of its kinetic energy, :math:`\\sum_i m_i x_i^2` with
  :math:`m_i` the row sums of M (a lumped energy: every share lies in [0, 1]), on the p
  functions at each end (``boundary_share``), and the distance of its largest coefficient
  from the nearest end, in control points (``peak``); a repeated top frequency is read over
  its whole eigenspace (summed squares, independent of the basis a solver returns);
* ``limit``: the outliers as :math:`N \\to \\infty` (the bar). Far from the ends the rows of
  :math:`K - \\lambda M` are the lattice's Toeplitz rows :math:`\\sum_L (k_L - \\lambda m_L)
  x_{i+L} = 0` (bandwidth w), whose decaying solutions are :math:`x_j = \\sum_k c_k z_k^j`,
  :math:`z_k` the w roots inside the unit circle of :math:`\\sum_L (k_L - \\lambda m_L) z^L`
  (for :math:`\\lambda` above the lattice's band there are exactly w). The first R rows, where
  the end changes the entries, then give a square boundary block :math:`B(\\lambda)` in the
  unknowns :math:`x_0, \\dots, x_{R-w-1}, c_1, \\dots, c_w`: the semi-infinite patch has the
  outlier :math:`\\lambda` exactly where :math:`\\det B(\\lambda) = 0`. Each root is refined
  from the mesh's value by the secant method in mpmath at :data:`LIMIT_DIGITS` digits (the
  finite mesh differs from it by :math:`O(|z|^{2N})`); no closed form is sought.

>>> from dispersion.discretization.finite_mesh.finite_patch import finite_bar
>>> o = outliers(finite_bar(2, 60, ends="free", mass="lumped", length=60.0))
>>> o.count, round(o.ratio, 4), [round(float(v), 10) for v in o.limit]
(2, 1.8943, [2.320030496])

References
----------
J. A. Cottrell, A. Reali, Y. Bazilevs, T. J. R. Hughes, CMAME 195 (2006) 5257-5296. A.
Boettcher, B. Silbermann, *Introduction to Large Truncated Toeplitz Matrices*, Springer 1999
(eigenvalues of Toeplitz-plus-corner operators outside the symbol's range).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dispersion.errors import ConvergenceError

__all__ = ["Outliers", "outliers", "boundary_limit", "LIMIT_DIGITS", "ABOVE"]

#: Working digits of the limit's refinement.
LIMIT_DIGITS = 20
#: A mesh frequency counts as an outlier above omega_l (1 + ABOVE).
ABOVE = 1e-9
#: Relative distance within which two frequencies (or two amplitudes) are one: the top
#: mode's layout is read over the whole space of a repeated top frequency.
TIE = 1e-8


@dataclass(frozen=True, repr=False)
class Outliers:
    """The outlier numbers of one patch (module docstring); frequencies in the patch's unit
    (the bar: :math:`\\omega` for its element length; ``ratio`` is unit-free)."""

    patch: object
    lattice: float
    omega_max: float
    count: int
    boundary_share: float
    peak: int
    limit: tuple
    top: tuple

    @property
    def ratio(self) -> float:
        return self.omega_max / self.lattice

    def __repr__(self) -> str:
        return (f"Outliers({self.patch.label()}: {self.count} above the lattice, ratio "
                f"{self.ratio:.6g})")


def _top_mode_layout(pen, X: np.ndarray) -> tuple[float, int]:
    """Share and peak of the top eigenspace spanned by the columns of ``X`` (one column: a
    simple top frequency). Both read the squared amplitudes summed over the columns, which do
    not depend on the basis chosen in a repeated eigenvalue's space (the solver's choice varies
    between runs); ties of the largest amplitude (a symmetric mode) take the nearest end."""
    patch = pen.patch
    full = np.column_stack([pen.mode_on_mesh(x) for x in X.T])
    M = pen.matrices.mass
    d = patch.dofs_per_point
    per = 1 if patch.model == "bar" else patch.n
    nx = patch.n_x
    sq = (full ** 2).sum(axis=1)
    amp = sq.reshape(nx, per * d).max(axis=1)
    top = np.flatnonzero(amp >= amp.max() * (1 - TIE))
    peak = int(min(min(i, nx - 1 - i) for i in top))
    if M is None:
        return float("nan"), peak
    weight = np.asarray(M.sum(axis=1)).ravel()  # the row sums: a lumped kinetic energy
    energy = (weight[:, None] * sq.reshape(-1, d)).sum(axis=1).reshape(nx, per).sum(1)
    p = patch.p
    near = np.r_[np.arange(p), np.arange(nx - p, nx)]
    total = energy.sum()
    return float(energy[near].sum() / total) if total > 0 else float("nan"), peak


def outliers(patch, *, limit: bool = True, spectrum=None) -> Outliers:
    """The outlier numbers of ``patch`` (every frequency: moderate N); ``spectrum``: its
    :class:`~dispersion.discretization.finite_mesh.mesh_spectrum.MeshSpectrum` with vectors, if already
    computed."""
    from dispersion.discretization.finite_mesh.lattice_reference import lattice_omega_max
    from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
    from dispersion.discretization.finite_mesh.mesh_spectrum import all_frequencies

    if spectrum is None:
        pen = mesh_pencil(patch)
        s = all_frequencies(pen, vectors=True)
    else:
        s, pen = spectrum, spectrum.pencil
    lat = lattice_omega_max(patch)
    above = s.omega[s.omega > lat * (1 + ABOVE)]
    space = s.omega >= s.omega[-1] * (1 - TIE)   # the top frequency and its repeats
    share, peak = _top_mode_layout(pen, s.vectors[:, space])
    lim: tuple = ()
    if limit and patch.model == "bar" and above.size and pen.Z is None and pen.M is not None \
            and pen.massless.size == 0:
        lim = boundary_limit(pen, above, lat)
    return Outliers(patch, lat, float(s.omega[-1]), int(above.size), share, peak, lim,
                    tuple(float(v) for v in above[::-1]))


def _toeplitz_rows(A: np.ndarray, tol: float = 1e-13):
    """``(R, row)``: the first row R from which every row to the middle is the middle row
    shifted, and that row as ``{L: value}``."""
    n = A.shape[0]
    c = n // 2
    scale = np.abs(A).max()
    nz = np.flatnonzero(np.abs(A[c]) > tol * scale)
    row = {int(j - c): float(A[c, j]) for j in nz}
    w = max(abs(L) for L in row)
    R = c
    for i in range(c, w - 1, -1):
        ok = all(abs(A[i, i + L] - v) <= tol * scale for L, v in row.items()) and \
            np.count_nonzero(np.abs(A[i]) > tol * scale) == len(row)
        if not ok:
            break
        R = i
    return R, row, w


def boundary_limit(pen, approximations, lattice: float) -> tuple:
    """The semi-infinite left end's outlier frequencies (mpmath numbers), refined from
    ``approximations`` (the mesh's outliers); :class:`ConvergenceError` if a refinement
    leaves the band or does not converge."""
    import mpmath

    K = pen.K.toarray()
    M = pen.M.toarray()
    Rk, krow, wk = _toeplitz_rows(K)
    Rm, mrow, wm = _toeplitz_rows(M)
    w = max(wk, wm)
    R = max(Rk, Rm, w)
    mp = mpmath.mp.clone()
    mp.dps = LIMIT_DIGITS
    Kb = [[mp.mpf(float(K[i, j])) for j in range(R + w)] for i in range(R)]
    Mb = [[mp.mpf(float(M[i, j])) for j in range(R + w)] for i in range(R)]
    kl = {L: mp.mpf(v) for L, v in krow.items()}
    ml = {L: mp.mpf(v) for L, v in mrow.items()}
    head = R - w

    def det(lam):
        coeffs = [kl.get(L, 0) - lam * ml.get(L, 0) for L in range(w, -w - 1, -1)]
        roots = mp.polyroots(coeffs, maxsteps=200, extraprec=2 * mp.dps)
        inside = sorted(roots, key=lambda z: abs(z))[:w]
        B = mp.matrix(R, R)
        for i in range(R):
            for j in range(R + w):
                a = Kb[i][j] - lam * Mb[i][j]
                if a == 0:
                    continue
                if j < head:
                    B[i, j] += a
                else:
                    for k, z in enumerate(inside):
                        B[i, head + k] += a * z ** j
        return mp.det(B)

    out = []
    h = pen.patch.element_length
    for approx in sorted(set(np.round(np.asarray(approximations, float), 9)), reverse=True):
        lam0 = mp.mpf(float((approx * h) ** 2))
        try:
            root = mp.findroot(det, (lam0, lam0 * (1 + mp.mpf(10) ** -8)), solver="secant",
                               tol=mp.mpf(10) ** (-2 * LIMIT_DIGITS + 10), maxsteps=60)
        except (ValueError, ZeroDivisionError) as exc:
            raise ConvergenceError(f"the boundary block's root near {approx:.10g} did not "
                                   f"converge ({exc})") from None
        root = mp.re(root)
        if not root > (lattice * h) ** 2:
            raise ConvergenceError(f"the boundary root {root} fell into the lattice's band")
        value = mp.sqrt(root) / h
        if not any(abs(value - v) <= mp.mpf(10) ** -20 * value for v in out):
            out.append(value)
    return tuple(out)
