"""The periodic bar of C0 Lagrange (spectral) elements: p DOFs a cell, p branches.

A cell of one unit element carries its left end node and its p - 1 interior nodes; a Bloch
wave :math:`u_{j+1} = e^{i\\theta} u_j` couples the element's right end to the next cell.
The p x p Hermitian pencil :math:`(P^H K_e P, P^H M_e P)` (:func:`bloch_pencil`) has p
branches; the lowest over :math:`\\theta \\in [0, \\pi]` is the acoustic one, whose exact
series is :func:`dispersion.splines.lagrange_sem.acoustic_series`. The critical step of
central differences is :math:`2/\\omega_{max}` over every branch and phase
(:func:`sem_bar_omega_max`): a grid refined inside, exact at a zone end (the pencil is real
there and its characteristic polynomial is rational).

>>> round(float(sem_bar_omega_max("sem-lumped", 1)[0]), 12)   # p = 1: the lumped linear bar
2.0
"""
from __future__ import annotations

import math

import numpy as np

from dispersion.errors import check_positive_int

__all__ = ["bloch_pencil", "sem_bar_frequency", "sem_bar_omega_max"]


def _element(mass: str, p: int):
    from dispersion.splines.lagrange_sem import element_matrices

    K, M = element_matrices(mass, p)
    return np.array(K, dtype=float), np.array(M, dtype=float)


def bloch_pencil(mass: str, p: int, theta: float):
    """Complex p x p matrices ``K(theta), M(theta)`` of the periodic C0 bar (unit elements)."""
    p = check_positive_int("degree p", p)
    Ke, Me = _element(mass, p)
    P = np.zeros((p + 1, p), dtype=complex)
    P[:p, :p] = np.eye(p)
    P[p, 0] = np.exp(1j * theta)
    return P.conj().T @ Ke @ P, P.conj().T @ Me @ P


def _branches(mass: str, p: int, theta) -> np.ndarray:
    import scipy.linalg as sla

    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    out = np.empty((theta.size, p))
    for i, t in enumerate(theta):
        K, M = bloch_pencil(mass, p, t)
        out[i] = np.sort(sla.eigh(K, M, eigvals_only=True))
    return out


def sem_bar_frequency(mass: str, p: int, theta) -> np.ndarray:
    """Acoustic :math:`\\omega h / c` at :math:`\\theta = kh \\in [0, \\pi]` (float array)."""
    lam = _branches(mass, p, theta)[:, 0]
    return np.sqrt(np.clip(lam, 0, None)).reshape(np.shape(theta))


def sem_bar_omega_max(mass: str, p: int, n_theta: int = 65):
    """``(omega_max, exact or None, theta, method)`` of the periodic C0 bar over every branch."""
    import sympy
    from scipy.optimize import minimize_scalar

    theta = np.linspace(0.0, math.pi, n_theta)
    top = _branches(mass, p, theta)[:, -1]
    i = int(np.argmax(top))
    if 0 < i < n_theta - 1:
        res = minimize_scalar(lambda t: -float(_branches(mass, p, t)[0, -1]),
                              bounds=(theta[i - 1], theta[i + 1]), method="bounded",
                              options={"xatol": 1e-12})
        return (math.sqrt(-res.fun), None, float(res.x),
                f"numeric: grid of {n_theta} phases, bounded refinement")
    from dispersion.splines.lagrange_sem import element_matrices

    Ke, Me = (sympy.Matrix(m) for m in element_matrices(mass, p))
    sign = 1 if i == 0 else -1  # e^{i theta} = +-1 at the zone ends
    P = sympy.zeros(p + 1, p)
    for k in range(p):
        P[k, k] = 1
    P[p, 0] = sign
    lam = sympy.Symbol("lam")
    poly = sympy.Poly((P.T * (Ke - lam * Me) * P).det(method="berkowitz"), lam)
    root = max(poly.real_roots(), key=lambda v: sympy.N(v, 40))
    exact = sympy.sqrt(root)
    return float(sympy.N(exact, 20)), exact, float(theta[i]), \
        f"exact at the zone end (grid of {n_theta} phases found no larger)"
