"""Through-thickness mode shapes, exact and discrete, and branch pairing by mode shape (MAC).

A Lamb mode :math:`\\mathbf u = (i U_x(y), U_y(y)) e^{i(kx - \\omega t)}` of the plate
:math:`-h \\le y \\le h` (y in units of h) has, with the Lame potentials
:math:`\\phi = A\\,\\Phi(y)`, :math:`\\psi = i B\\,\\Psi(y)` written with the entire functions
:math:`C(z) = \\cos\\sqrt z` and :math:`S(z) = \\sin\\sqrt z/\\sqrt z` (real for real P, Q),

- symmetric: :math:`\\Phi = C(P y^2)`, :math:`\\Psi = y\\,S(Q y^2)`;
- antisymmetric: :math:`\\Phi = y\\,S(P y^2)`, :math:`\\Psi = C(Q y^2)`;

:math:`U_x = \\kappa \\Phi A + \\Psi' B`, :math:`U_y = \\Phi' A + \\kappa \\Psi B`, and (A, B)
spans the null space of the traction-free conditions at y = 1,

.. math::

    \\begin{pmatrix} 2\\kappa\\Phi'(1) & (\\kappa^2 - Q)\\Psi(1) \\\\
    (\\kappa^2 - Q)\\Phi(1) & 2\\kappa\\Psi'(1) \\end{pmatrix}
    \\begin{pmatrix} A \\\\ B \\end{pmatrix} = 0,

whose determinant is :math:`-F` of :mod:`dispersion.waves.rayleigh_lamb` (so it is singular exactly
on the branches). The discrete shape is the B-spline field of the control values through the
thickness, sampled at the same points. The modal assurance criterion
:math:`\\mathrm{MAC}(a, b) = (a^T b)^2 / (a^T a\\, b^T b)` pairs each exact branch with the
discrete mode it resembles most (an assignment maximising the total MAC), so an error curve
compares like with like even where the discrete spectrum orders its modes differently.

>>> import numpy as np
>>> y = np.linspace(-1, 1, 5)
>>> ux, uy = exact_mode_shape("S", 1e-3, 1.690308e-3, 0.3, y)   # S0: u_x uniform
>>> bool(np.allclose(ux / ux[0], 1.0, atol=1e-6))
True

References
----------
J. L. Rose, *Ultrasonic waves in solid media*, 2004, ch. 8 (mode shapes);
R. J. Allemang, Sound and Vibration 37 (2003) 14-23 (the modal assurance criterion).
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from dispersion.symbolic.bspline import SplineBasis1D, open_knot_vector
from dispersion.errors import InputError, check_nu
from dispersion.symbolic.plate import PlatePatch, numeric_pencil, with_nu
from dispersion.waves.numeric_frequency import cos_sqrt, sinc_sqrt
from dispersion.waves.rayleigh_lamb import speed_ratio_squared

__all__ = [
    "PairedBranches",
    "discrete_mode_shape",
    "discrete_modes",
    "exact_mode_fields",
    "exact_mode_shape",
    "mac",
    "pair_by_shape",
]

#: Default sample points through the thickness (y / h).
SAMPLES = np.linspace(-1.0, 1.0, 21)
#: Below this MAC a pair is not trusted and the error is not reported (NaN).
MAC_MIN = 0.5
#: How :func:`exact_mode_fields` scales its fields (headers and captions quote it).
FIELD_NORMALISATION = "max |u| = 1; stresses in mu max|u| / h; y from the mid-plane"


def _profiles(kind: str, P: float, Q: float, y: np.ndarray):
    """Phi, Phi', Psi, Psi' at y (entire-function forms, real for real P and Q)."""
    z_p, z_q = P * y**2, Q * y**2
    if kind == "S":
        Phi, dPhi = cos_sqrt(z_p), -P * y * sinc_sqrt(z_p)
        Psi, dPsi = y * sinc_sqrt(z_q), cos_sqrt(z_q)
    elif kind == "A":
        Phi, dPhi = y * sinc_sqrt(z_p), cos_sqrt(z_p)
        Psi, dPsi = cos_sqrt(z_q), -Q * y * sinc_sqrt(z_q)
    else:
        raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
    return Phi, dPhi, Psi, dPsi


def _amplitudes(kind: str, kappa: float, Omega: float, nu: float):
    """(A, B), the potentials' amplitudes: a null vector of the traction-free conditions."""
    s = speed_ratio_squared(nu)
    k2, W2 = kappa**2, Omega**2
    P, Q = s * W2 - k2, W2 - k2
    Phi1, dPhi1, Psi1, dPsi1 = (float(v) for v in _profiles(kind, P, Q, np.array(1.0)))
    a, b = 2 * kappa * dPhi1, (k2 - Q) * Psi1
    c, d = (k2 - Q) * Phi1, 2 * kappa * dPsi1
    # null vector of [[a, b], [c, d]] from the row with more weight (the other is ~ its multiple)
    A, B = (b, -a) if a * a + b * b >= c * c + d * d else (d, -c)
    if A == 0 and B == 0:
        A, B = 1.0, 0.0  # kappa = 0 and both rows vanish: a pure longitudinal/shear cut-off
    return A, B, P, Q


def exact_mode_shape(kind: str, kappa: float, Omega: float, nu: float, y=SAMPLES):
    """:math:`(U_x, U_y)` of the exact mode at a root :math:`(\\kappa, \\Omega)`, unit norm.

    ``y`` in units of h (-1 bottom, 1 top). :math:`u_x = i U_x`: the in-plane displacement
    lags the transverse one by a quarter period.
    """
    nu = float(check_nu(nu))
    y = np.asarray(y, dtype=float)
    A, B, P, Q = _amplitudes(kind, kappa, Omega, nu)
    Phi, dPhi, Psi, dPsi = _profiles(kind, P, Q, y)
    ux, uy = kappa * Phi * A + dPsi * B, dPhi * A + kappa * Psi * B
    norm = np.sqrt(np.sum(ux**2 + uy**2))
    if not norm > 0:
        # (kappa, Omega) = (0, 0): the rigid limits of S0 (u_x uniform) and A0 (u_y uniform)
        ux, uy = (np.ones_like(y), np.zeros_like(y)) if kind == "S" else \
            (np.zeros_like(y), np.ones_like(y))
        norm = np.sqrt(np.sum(ux**2 + uy**2))
    return ux / norm, uy / norm


def exact_mode_fields(kind: str, kappa: float, Omega: float, nu: float, y=SAMPLES) -> dict:
    """Displacements and stresses of the exact mode through the thickness.

    With :math:`u_x = i U_x e^{i(kx-\\omega t)}`, :math:`u_y = U_y e^{i(kx-\\omega t)}`
    (y and :math:`U` in units of h), :math:`\\Phi'' = -P\\Phi`, :math:`\\Psi'' = -Q\\Psi` and
    :math:`\\lambda/\\mu = c_L^2/c_T^2 - 2`:

    .. math::

        \\frac{\\sigma_{xx}}{\\mu} = \\frac{\\lambda}{\\mu}(U_y' - \\kappa U_x)
            - 2\\kappa U_x, \\quad
        \\frac{\\sigma_{yy}}{\\mu} = \\frac{\\lambda}{\\mu}(U_y' - \\kappa U_x) + 2 U_y',
        \\quad \\frac{\\sigma_{xy}}{i\\mu} = U_x' + \\kappa U_y .

    Normalised to :math:`\\max(|U_x|, |U_y|) = 1`; the faces are traction free
    (:math:`\\sigma_{yy} = \\sigma_{xy} = 0` at :math:`y = \\pm 1`).

    >>> f = exact_mode_fields("A", 1.0, 0.6503451591550, 0.3, [-1.0, 1.0])
    >>> bool(abs(f["sigma_yy"]).max() < 1e-10 and abs(f["sigma_xy"]).max() < 1e-10)
    True
    """
    nu = float(check_nu(nu))
    y = np.asarray(y, dtype=float)
    A, B, P, Q = _amplitudes(kind, kappa, Omega, nu)
    Phi, dPhi, Psi, dPsi = _profiles(kind, P, Q, y)
    ddPhi, ddPsi = -P * Phi, -Q * Psi
    ux, uy = kappa * Phi * A + dPsi * B, dPhi * A + kappa * Psi * B
    dux, duy = kappa * dPhi * A + ddPsi * B, ddPhi * A + kappa * dPsi * B
    lam = 1 / speed_ratio_squared(nu) - 2
    div = duy - kappa * ux
    scale = max(float(np.max(np.abs(ux))), float(np.max(np.abs(uy))))
    if not scale > 0:
        raise InputError(f"no mode shape at kappa={kappa}, Omega={Omega} (zero field)")
    return {"y": y, "u_x": ux / scale, "u_y": uy / scale,
            "sigma_xx": (lam * div - 2 * kappa * ux) / scale,
            "sigma_yy": (lam * div + 2 * duy) / scale,
            "sigma_xy": (dux + kappa * uy) / scale}


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
    (as in :func:`dispersion.waves.discrete_branches.discrete_branches`).
    """
    patch = with_nu(patch, nu)
    from dispersion.waves.extended_pencil import refine_inaccurate
    from dispersion.waves.pencil_frequencies import pencil_frequencies

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
    dropped (NaN). ``exact`` is a :class:`dispersion.waves.exact_branches.ExactBranches`.
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
