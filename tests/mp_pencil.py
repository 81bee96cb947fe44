"""Independent extended-precision reference for the discrete pencil (tests only).

K and M are assembled in mpmath from :func:`dispersion.symbolic.plate.stiffness_terms` and the
closed forms of the x-functions (x-exact: m = 1, s = kappa, d = kappa^2; Bloch: the cosine and
sine sums of the Gram integrals), massless DOFs condensed by the Schur complement, and the
eigenvalues found by ``mpmath.eigsy`` after a Cholesky reduction. Nothing of the
characteristic-polynomial path of :mod:`dispersion.discretization.pencil_polynomial` is used.
"""
from __future__ import annotations

import mpmath
import sympy

from dispersion.symbolic.plate import bloch_coefficients, mass_block, stiffness_terms


def _mpf(v) -> mpmath.mpf:
    v = sympy.Rational(v)
    return mpmath.mpf(int(v.p)) / int(v.q)


def _moduli(nu) -> dict:
    """The plane-strain D over the shear modulus, in mpmath, from the constants themselves:
    Poisson's ratio ``nu`` (taken by its decimal; Lame constants), or the stiffnesses
    ``c11, c22, c12, c66`` of an orthotropic law."""
    if hasattr(nu, "c66"):
        c66 = _mpf(nu.c66)
        return {"D11": _mpf(nu.c11) / c66, "D22": _mpf(nu.c22) / c66,
                "D12": _mpf(nu.c12) / c66, "D66": mpmath.mpf(1)}
    nu = _mpf(sympy.Rational(str(nu)))
    lam = 2 * nu / (1 - 2 * nu)
    return {"D11": lam + 2, "D22": lam + 2, "D12": lam, "D66": mpmath.mpf(1)}


def mp_pencil(patch, nu, kappa):
    """K, M (mpmath matrices, current precision) at ``kappa``; nu taken by its decimal, or
    an orthotropic law (:func:`_moduli`)."""
    mat = _moduli(nu)
    k = mpmath.mpf(kappa)
    if patch.model == "x-exact":
        xf = {"m": mpmath.mpf(1), "s": k, "d": k**2}
    else:
        c = bloch_coefficients(patch.p)
        r = _mpf(patch.r)
        th = k * r
        xf = {"m": sum(_mpf(v) * mpmath.cos(L * th) for L, v in c["00"].items()),
              "s": -2 / r * sum(_mpf(c["10"][L]) * mpmath.sin(L * th)
                                for L in range(1, patch.p + 1)),
              "d": sum(_mpf(v) * mpmath.cos(L * th) for L, v in c["11"].items()) / r**2}
    if patch.model == "x-exact" or patch.x_lumped:
        mx = mpmath.mpf(1)
    else:  # the x-direction mass rule: m_x = sum_L c_L cos(L theta)
        mx = sum(_mpf(v) * mpmath.cos(L * th) for L, v in patch.x_mass)
    n2 = 2 * patch.n
    K = mpmath.zeros(n2, n2)
    for m, f, B in stiffness_terms(patch):
        K += mat[m] * xf[f] * mpmath.matrix([[_mpf(v) for v in row] for row in B.tolist()])
    if patch.model == "bloch":  # a Petrov-Galerkin rule's test functions along x: K times
        # the Bloch symbol of its x-factor (1 for every Galerkin rule)
        K *= sum(_mpf(v) * mpmath.cos(L * th) for L, v in patch.x_stiffness)
    M = mx * mpmath.matrix([[_mpf(v) for v in row] for row in mass_block(patch).tolist()])
    return K, M


def mp_frequencies(patch, nu, kappa, dps: int = 60, basis=None) -> list:
    """All finite Omega at ``kappa``, ascending, as mpf (``dps`` digits); with ``basis`` (an
    integer mirror basis) those of the projected block."""
    with mpmath.workdps(dps):
        K, M = mp_pencil(patch, nu, kappa)
        if basis is not None:
            E = mpmath.matrix([[int(v) for v in row] for row in basis.tolist()])
            K, M = E.T * K * E, E.T * M * E
        n2 = K.rows
        zero = [i for i in range(n2) if all(M[i, j] == 0 for j in range(n2))]
        keep = [i for i in range(n2) if i not in zero]

        def sub(A, rows, cols):
            return mpmath.matrix([[A[i, j] for j in cols] for i in rows])

        Kr = sub(K, keep, keep)
        if zero:
            Kr -= sub(K, keep, zero) * mpmath.inverse(sub(K, zero, zero)) * sub(K, zero, keep)
        L = mpmath.cholesky(sub(M, keep, keep))
        Li = mpmath.inverse(L)
        A = Li * Kr * Li.T
        A = (A + A.T) / 2
        lam = sorted(mpmath.eigsy(A, eigvals_only=True))
        return [mpmath.sqrt(max(v, 0)) for v in lam]


def mp_group_velocities(patch, nu, kappa, dps: int = 80, basis=None) -> list:
    """:math:`d\\Omega/d\\kappa` of every root (ascending) by a central difference at ``dps``
    digits, step 1e-12 kappa (truncation ~1e-24 relative, rounding ~1e-(dps-12) of the
    largest root over the smallest)."""
    with mpmath.workdps(dps):
        k = mpmath.mpf(kappa)
        h = k * mpmath.mpf(10) ** -12
        up = mp_frequencies(patch, nu, k + h, dps, basis)
        dn = mp_frequencies(patch, nu, k - h, dps, basis)
        return [(a - b) / (2 * h) for a, b in zip(up, dn)]


def mp_group_velocity(patch, nu, kappa, index: int, dps: int = 80):
    """The ``index``-th of :func:`mp_group_velocities`."""
    return mp_group_velocities(patch, nu, kappa, dps)[index]
