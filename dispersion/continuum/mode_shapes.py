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

whose determinant is :math:`-F` of :mod:`dispersion.continuum.rayleigh_lamb` (so it is singular exactly
on the branches). The discrete shape is the B-spline field of the control values through the
thickness, sampled at the same points. The modal assurance criterion
:math:`\\mathrm{MAC}(a, b) = (a^T b)^2 / (a^T a\\, b^T b)` pairs each exact branch with the
discrete mode it resembles most (an assignment maximising the total MAC), so an error curve
compares like with like even where the discrete spectrum orders its modes differently. The
discrete shapes and the pairing live with the lattice, in
:mod:`dispersion.discretization.discrete_mode_shapes`.

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

import numpy as np

from dispersion.errors import InputError, check_nu
from dispersion.continuum.numeric_frequency import cos_sqrt, sinc_sqrt
from dispersion.continuum.rayleigh_lamb import speed_ratio_squared

__all__ = [
    "exact_mode_fields",
    "exact_mode_shape",
]

#: Default sample points through the thickness (y / h).
SAMPLES = np.linspace(-1.0, 1.0, 21)
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
