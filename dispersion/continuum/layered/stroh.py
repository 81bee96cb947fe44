"""The Stroh (state-vector) form of one layer: the first-order system through the thickness.

For a wave :math:`u(x_1, x_3, t) = U(x_3) e^{i(\\kappa x_1 - \\Omega t)}` (units of
:class:`~dispersion.continuum.layered.layered_plate.ScaledStack`) the displacement U and the traction
on the planes :math:`x_3 = const`, :math:`T = (\\sigma_{13}, \\sigma_{23}, \\sigma_{33})`,
obey :math:`\\xi' = A \\xi` with :math:`\\xi = (U, T)` and

.. math::

    A = \\begin{bmatrix} -i\\kappa\\, Q_{zz}^{-1} Q_{zx} & Q_{zz}^{-1} \\\\
        \\kappa^2 (Q_{xx} - Q_{xz} Q_{zz}^{-1} Q_{zx}) - \\rho\\Omega^2 I &
        -i\\kappa\\, Q_{xz} Q_{zz}^{-1} \\end{bmatrix},

:math:`(Q_{ab})_{ik} = C_{iakb}` (a, b the directions x = 1, z = 3). Across a layer of
thickness t, :math:`\\xi(x_3 + t) = e^{A t} \\xi(x_3)`: the transfer matrix, entire in
:math:`\\kappa` and :math:`\\Omega` (no partial waves, no branch points), which is what makes
the same formula serve isotropic, anisotropic and damped layers alike.

>>> import numpy as np
>>> C = np.zeros((6, 6)); C[:3, :3] = 1.0; C[[0, 1, 2], [0, 1, 2]] = 3.0; C[3:, 3:] = np.eye(3)
>>> A = system_matrix(C, 1.0, 0.5, 2.0)
>>> A.shape, bool(np.allclose(A[:3, 3:], np.diag([1, 1, 1 / 3])))
((6, 6), True)

References
----------
A. N. Stroh, J. Math. Phys. 41 (1962) 77; A. H. Nayfeh, *Wave propagation in layered
anisotropic media*, Elsevier 1995, sec. 4.2 (the state-vector form); S. I. Rokhlin,
L. Wang, JASA 112 (2002) 822 (thin-sublayer stiffness matrices).
"""
from __future__ import annotations

import numpy as np

__all__ = ["q_blocks", "system_parts", "system_matrix", "system_derivatives"]

# (i, a) -> Voigt index of the tensor pair
_V = np.array([[0, 5, 4], [5, 1, 3], [4, 3, 2]])


def q_blocks(C: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(Qxx, Qxz, Qzz)`` of a 6x6 Voigt stiffness: :math:`(Q_{ab})_{ik} = C_{iakb}`."""
    idx = np.arange(3)
    Qxx = C[_V[idx, 0][:, None], _V[idx, 0][None, :]]
    Qxz = C[_V[idx, 0][:, None], _V[idx, 2][None, :]]
    Qzz = C[_V[idx, 2][:, None], _V[idx, 2][None, :]]
    return Qxx, Qxz, Qzz


def _parts(C):
    Qxx, Qxz, Qzz = q_blocks(C)
    Zi = np.linalg.inv(Qzz)
    return Zi, Zi @ Qxz.T, Qxz @ Zi, Qxx - Qxz @ Zi @ Qxz.T


def system_parts(C: np.ndarray, rho: float) -> np.ndarray:
    """The constant parts of A: ``(4, 6, 6)`` complex, :math:`A = A_0 + \\kappa A_1 +
    \\kappa^2 A_2 + \\Omega^2 A_3` (computed once per layer, then A costs a few additions)."""
    Zi, ZQ, QZ, R = _parts(C)
    out = np.zeros((4, 6, 6), dtype=complex)
    out[0, :3, 3:] = Zi
    out[1, :3, :3] = -1j * ZQ
    out[1, 3:, 3:] = -1j * QZ
    out[2, 3:, :3] = R
    out[3, 3:, :3] = -rho * np.eye(3)
    return out


def system_matrix(C: np.ndarray, rho: float, kappa, omega, parts=None) -> np.ndarray:
    """A of the module docstring for every ``kappa`` (array, real or complex) at ``omega``
    (scalar or broadcastable): shape ``kappa.shape + (6, 6)``, complex. ``parts``: the
    layer's :func:`system_parts` when they are at hand."""
    kappa = np.asarray(kappa, dtype=complex)
    P = system_parts(C, rho) if parts is None else parts
    k = kappa[..., None, None]
    w2 = (np.asarray(omega, dtype=complex) ** 2)[..., None, None] if np.ndim(omega) else \
        complex(omega) ** 2
    return P[0] + k * (P[1] + k * P[2]) + w2 * P[3]


def system_derivatives(C: np.ndarray, rho: float, kappa, omega):
    """``(dA/dkappa, dA/dOmega)`` at each ``kappa``, shapes as :func:`system_matrix`."""
    kappa = np.asarray(kappa, dtype=complex)
    Zi, ZQ, QZ, R = _parts(C)
    k = kappa[..., None, None]
    shape = k.shape[:-2] + (6, 6)
    dk = np.zeros(shape, dtype=complex)
    dk[..., :3, :3] = -1j * ZQ
    dk[..., 3:, :3] = 2 * k * R
    dk[..., 3:, 3:] = -1j * QZ
    dw = np.zeros(shape, dtype=complex)
    dw[..., 3:, :3] = -2 * rho * complex(omega) * np.eye(3)
    return dk, dw
