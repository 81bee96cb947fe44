"""The semi-analytical finite element (SAFE) model of a layered plate: B-splines through the
thickness, every mode at once.

Each layer (of a :class:`~dispersion.continuum.layered.dynamic_stiffness.ModeClass`'s stack) is a
B-spline patch of degree p (:class:`~dispersion.splines.bspline.SplineBasis1D`), joined to
its neighbours with C0 continuity (the end functions of open knot vectors are shared) or by
springs. With :math:`u = N(x_3) \\mathbf u\\, e^{i(\\kappa x_1 - \\Omega t)}` the weak form gives

.. math::

    \\big(\\kappa^2 K_2 + i\\kappa K_1 + K_0 - \\Omega^2 M\\big)\\,\\mathbf u = 0, \\qquad
    K_2 = \\int N^T Q_{xx} N, \\quad K_1 = K_{xz}^T - K_{xz}, \\quad
    K_{xz} = \\int N^T Q_{xz} N', \\quad K_0 = \\int N'^T Q_{zz} N',

:math:`M = \\int \\rho N^T N` (K_1 real skew, so :math:`i\\kappa K_1` is Hermitian). At a
given :math:`\\kappa` the frequencies are the eigenvalues of a Hermitian pencil
(:func:`frequencies`); at a given :math:`\\Omega` the wavenumbers those of the quadratic
pencil, linearised to a generalised problem of twice the size (:func:`wavenumbers`):

.. math::

    \\begin{bmatrix} 0 & I \\\\ -(K_0 - \\Omega^2 M) & -iK_1 \\end{bmatrix}
    \\begin{bmatrix} \\mathbf u \\\\ \\kappa \\mathbf u \\end{bmatrix} = \\kappa
    \\begin{bmatrix} I & 0 \\\\ 0 & K_2 \\end{bmatrix}
    \\begin{bmatrix} \\mathbf u \\\\ \\kappa \\mathbf u \\end{bmatrix}.

The SAFE roots are approximations (their error falls with the elements as the B-splines'
order allows); the exact relation (:mod:`dispersion.continuum.layered.dynamic_stiffness`) polishes
and counts them (:mod:`dispersion.continuum.layered.layered_modes`).

References
----------
L. Gavric, "Computation of propagative waves in free rail using a finite element technique",
J. Sound Vib. 185 (1995) 531; I. Bartoli, A. Marzani, F. Lanza di Scalea, E. Viola,
J. Sound Vib. 295 (2006) 685 (SAFE with damping); D. A. Kiefer, GEWtool (2023),
doi:10.5281/zenodo.10114243 (the same pencils by spectral collocation).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.continuum.layered.dynamic_stiffness import ModeClass, class_stack
from dispersion.continuum.layered.stroh import q_blocks

__all__ = ["SafePencil", "safe_pencil", "wavenumbers", "frequencies", "SAFE_DEGREE",
           "elements_per_layer"]

#: Degree of the B-splines through the thickness.
SAFE_DEGREE = 4
#: Elements per unit of (largest through-thickness wavenumber x layer thickness). Rule: the
#: SAFE roots need only fall in the basin of the exact relation's polish (relative error
#: well below the spacing of neighbouring roots); 0.5 elements per radian at degree 4 keeps
#: the error of every root of the test plates below 1e-6 relative (measured, tests).
ELEMENTS_PER_RADIAN = 0.5


@dataclass(frozen=True)
class SafePencil:
    """The matrices of the module docstring for one class, with ``nodes`` (the x3 of each
    function's Greville point, from the class's first face) and ``components`` (the kept
    displacement components of each unknown)."""

    K2: np.ndarray
    K1: np.ndarray
    K0: np.ndarray
    M: np.ndarray
    component: np.ndarray
    node: np.ndarray


def elements_per_layer(stack, cls: ModeClass, omega_max: float, kappa_max: float) -> list:
    """Elements of each row of the class's stack: :data:`ELEMENTS_PER_RADIAN` times the
    largest wavenumber through it (the slowest bulk wave at omega_max, or kappa_max) times
    its thickness, at least 2."""
    from dispersion.continuum.layered.dynamic_stiffness import _kelvin_min

    rows, _, _ = class_stack(stack, cls)
    out = []
    for i, thick in rows:
        slow = math.sqrt(_kelvin_min(stack.C[i]) / stack.rho[i])
        q = max(omega_max / slow, kappa_max)
        out.append(max(2, math.ceil(ELEMENTS_PER_RADIAN * q * thick) + 1))
    return out


def safe_pencil(stack, cls: ModeClass, elements: list, degree: int = SAFE_DEGREE) -> SafePencil:
    """Assemble the SAFE matrices of the class (``elements``: per row of its stack)."""
    from dispersion.splines.bspline import SplineBasis1D

    rows, above, mid_spring = class_stack(stack, cls)
    dofs = np.array(cls.dofs)
    nc = dofs.size
    p = degree
    counts = [n + p for n in elements]
    # first global function of each row: shared end functions at perfect interfaces
    start, total = [], 0
    for r in range(len(rows)):
        if r > 0 and above[r - 1] is None:
            total -= 1
        start.append(total)
        total += counts[r]
    N = total * nc
    K2, K1, K0, M = (np.zeros((N, N), dtype=complex if not stack.lossless else float)
                     for _ in range(4))
    xg, wg = np.polynomial.legendre.leggauss(p + 1)
    z0 = 0.0
    node = np.zeros(total)
    for r, ((i, thick), n_el) in enumerate(zip(rows, elements)):
        basis = SplineBasis1D.uniform(p, n_el, z0, z0 + thick)
        Qxx, Qxz, Qzz = (Q[np.ix_(dofs, dofs)] for Q in q_blocks(stack.C[i]))
        node[start[r]:start[r] + counts[r]] = np.asarray(basis.kv.greville())
        for e in range(n_el):
            a, b = basis.spans[e]
            x = a + (b - a) * (xg + 1) / 2
            w = wg * (b - a) / 2
            act, Nv = basis.evaluate(x)
            _, dN = basis.evaluate(x, 1)
            act = act[0]
            INN = np.einsum("g,ga,gb->ab", w, Nv, Nv)
            INd = np.einsum("g,ga,gb->ab", w, Nv, dN)
            Idd = np.einsum("g,ga,gb->ab", w, dN, dN)
            gl = ((start[r] + act)[:, None] * nc + np.arange(nc)[None, :]).ravel()
            ix = np.ix_(gl, gl)
            Kxz = np.kron(INd, Qxz)
            K2[ix] += np.kron(INN, Qxx)
            K1[ix] += Kxz.T - Kxz
            K0[ix] += np.kron(Idd, Qzz)
            M[ix] += stack.rho[i] * np.kron(INN, np.eye(nc))
        z0 += thick
        if above[r] is not None:   # springs between this row's last and the next's first
            ks = stack.springs[above[r]][dofs]
            lo = (start[r] + counts[r] - 1) * nc + np.arange(nc)
            hi = start[r + 1] * nc + np.arange(nc)
            K0[lo, lo] += ks
            K0[hi, hi] += ks
            K0[lo, hi] -= ks
            K0[hi, lo] -= ks
    keep = np.ones(N, dtype=bool)
    if cls.half:
        first = np.arange(nc)
        if mid_spring is not None:
            ks = stack.springs[mid_spring][dofs]
            odd = np.isin(dofs, cls.mid_fixed)
            K0[first[odd], first[odd]] += 2 * ks[odd]
        else:
            keep[first[np.isin(dofs, cls.mid_fixed)]] = False
    component = np.tile(dofs, total)[keep]
    nodes = np.repeat(node, nc)[keep]
    sel = np.ix_(keep, keep)
    return SafePencil(K2[sel], K1[sel], K0[sel], M[sel], component, nodes)


def wavenumbers(pencil: SafePencil, omega: float) -> np.ndarray:
    """Every eigenvalue :math:`\\kappa` of the pencil at ``omega`` (complex, all of them:
    propagating, evanescent and their mirror images)."""
    from scipy.linalg import eig

    n = pencil.K0.shape[0]
    Z, I = np.zeros((n, n)), np.eye(n)
    A = np.block([[Z, I], [-(pencil.K0 - omega**2 * pencil.M), -1j * pencil.K1]])
    B = np.block([[I, Z], [Z, pencil.K2]])
    return eig(A, B, right=False)


def frequencies(pencil: SafePencil, kappa: float, count: int | None = None) -> np.ndarray:
    """The frequencies :math:`\\Omega \\ge 0` of the pencil at a real ``kappa``, ascending
    (undamped plates); with ``count`` only the lowest ``count`` of them (a partial
    eigensolver: cheaper when they are few)."""
    from scipy.linalg import eigh

    K = kappa**2 * pencil.K2 + 1j * kappa * pencil.K1 + pencil.K0
    n = K.shape[0]
    subset = None if count is None or count >= n else [0, max(count, 1) - 1]
    w2 = eigh(K, pencil.M, eigvals_only=True, subset_by_index=subset)
    return np.sqrt(np.maximum(w2, 0.0))
