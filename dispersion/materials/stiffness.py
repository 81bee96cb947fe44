"""The elastic law of a solid in three dimensions: its 6x6 stiffness in Voigt notation.

Axes: :math:`x_1` along the plate (the wave's direction once a plate is turned to it),
:math:`x_2` in the plate's plane, :math:`x_3` along the normal (through the thickness). Voigt
order 1 = 11, 2 = 22, 3 = 33, 4 = 23, 5 = 13, 6 = 12, so that

.. math::

    \\sigma_\\alpha = C_{\\alpha\\beta} \\varepsilon_\\beta, \\qquad
    \\varepsilon = (\\varepsilon_{11}, \\varepsilon_{22}, \\varepsilon_{33},
    2\\varepsilon_{23}, 2\\varepsilon_{13}, 2\\varepsilon_{12}).

A :class:`Stiffness` is a frozen value in Pa; the factories make one from the constants a
practitioner has: :func:`isotropic` (Lame constants, or E and nu), :func:`from_speeds` (bulk
speeds and density), :func:`transversely_isotropic` (a unidirectional ply, fibres along
:math:`x_1`, from its engineering constants), :func:`orthotropic` (nine constants) and
:func:`voigt` (any symmetric positive definite 6x6). :meth:`Stiffness.rotated` turns the
material about the normal (a ply angle); :meth:`Stiffness.with_loss` makes the moduli complex
(hysteretic damping, loss factor eta, time dependence :math:`e^{-i\\omega t}`, so
:math:`C^* = C (1 - i\\eta)` and waves decay as they travel).

The plane-strain law of the plate patch (:mod:`dispersion.materials.elastic_law`) is the
:math:`x_1 x_3` block of this one: :meth:`Stiffness.plane_strain_law`.

>>> steel = isotropic(lam=115.6e9, mu=78.99e9)
>>> round(steel.matrix[0][0] / 1e9, 2), round(steel.matrix[3][3] / 1e9, 2)
(273.58, 78.99)
>>> ply = transversely_isotropic(E1=142e9, E2=10.3e9, G12=7.2e9, nu12=0.27, nu23=0.54)
>>> turned = ply.rotated(90)
>>> abs(turned.matrix[1][1] - ply.matrix[0][0]) < 1e-3 * ply.matrix[0][0]
True

References
----------
B. A. Auld, *Acoustic fields and waves in solids*, vol. 1, 2nd ed., Krieger 1990, ch. 3
(Voigt notation, the Bond transformation); R. M. Jones, *Mechanics of composite materials*,
2nd ed., 1999, sec. 2.2-2.6 (engineering constants, positive definiteness); A. H. Nayfeh,
*Wave propagation in layered anisotropic media*, Elsevier 1995, ch. 3 (complex moduli).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.errors import InputError, as_real, check_positive

__all__ = ["Stiffness", "isotropic", "from_speeds", "transversely_isotropic", "orthotropic",
           "voigt", "VOIGT_PAIRS"]

#: Voigt index (0-based) -> tensor index pair.
VOIGT_PAIRS = ((0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1))
_INDEX = np.array([[0, 5, 4], [5, 1, 3], [4, 3, 2]])


def _tensor(C: np.ndarray) -> np.ndarray:
    return C[_INDEX[:, :, None, None], _INDEX[None, None, :, :]]


def _voigt(c: np.ndarray) -> np.ndarray:
    out = np.empty((6, 6), dtype=c.dtype)
    for a, (i, j) in enumerate(VOIGT_PAIRS):
        for b, (k, m) in enumerate(VOIGT_PAIRS):
            out[a, b] = c[i, j, k, m]
    return out


def _kelvin(C: np.ndarray) -> np.ndarray:
    """The Kelvin (Mandel) form: Voigt with the shear rows and columns scaled by sqrt 2, so
    that its eigenvalues bound :math:`\\varepsilon : C : \\varepsilon / \\varepsilon :
    \\varepsilon`."""
    w = np.array([1, 1, 1, math.sqrt(2), math.sqrt(2), math.sqrt(2)])
    return C * w[:, None] * w[None, :]


@dataclass(frozen=True)
class Stiffness:
    """A 6x6 stiffness in Voigt notation, in Pa (``matrix``: rows of floats, or complex
    numbers where the law is damped), with ``kind`` naming the factory that made it.

    Valid: finite, symmetric, and the real part positive definite (a lossy law's imaginary
    part is the loss; it must not make energy: its Kelvin form is negative semidefinite).
    """

    matrix: tuple
    kind: str = "anisotropic"

    def __post_init__(self):
        try:
            C = np.array(self.matrix, dtype=complex)
        except (TypeError, ValueError):
            raise InputError("stiffness must be a 6x6 array of numbers") from None
        if C.shape != (6, 6) or not np.all(np.isfinite(C)):
            raise InputError(f"stiffness must be a 6x6 array of finite numbers, got shape "
                             f"{C.shape}")
        scale = np.max(np.abs(C))
        if not scale > 0:
            raise InputError("stiffness must not be zero")
        if np.max(np.abs(C - C.T)) > 1e-12 * scale:
            raise InputError("stiffness must be symmetric (C_ab = C_ba)")
        C = (C + C.T) / 2
        lam = np.linalg.eigvalsh(_kelvin(C.real))
        if not lam[0] > 1e-9 * lam[-1]:
            raise InputError("stiffness must be positive definite (its smallest Kelvin "
                             f"eigenvalue is {lam[0]:.4g} Pa, the largest {lam[-1]:.4g} Pa)")
        if np.any(C.imag != 0) and np.linalg.eigvalsh(_kelvin(C.imag))[-1] > 1e-12 * scale:
            raise InputError("a damped stiffness must lose energy: with e^(-i omega t) its "
                             "imaginary part must be negative semidefinite (C (1 - i eta), "
                             "eta >= 0)")
        lossless = not np.any(C.imag != 0)
        rows = tuple(tuple(float(v.real) if lossless else complex(v) for v in row) for row in C)
        object.__setattr__(self, "matrix", rows)

    # ------------------------------------------------------------------ numbers

    def array(self) -> np.ndarray:
        """The 6x6 matrix (float, or complex if damped)."""
        return np.array(self.matrix, dtype=float if self.lossless else complex)

    @property
    def lossless(self) -> bool:
        """True without damping (real moduli)."""
        return not any(isinstance(v, complex) for row in self.matrix for v in row)

    def kelvin_min(self) -> float:
        """Smallest eigenvalue of the Kelvin form of the real part (Pa): for every strain,
        :math:`\\varepsilon : \\mathrm{Re}\\,C : \\varepsilon \\ge` this times
        :math:`\\varepsilon : \\varepsilon`."""
        return float(np.linalg.eigvalsh(_kelvin(self.array().real))[0])

    def rotated(self, degrees: float) -> Stiffness:
        """The material turned by ``degrees`` about the normal :math:`x_3` (counterclockwise
        seen from +x3): a ply whose fibres (its axis 1) lie at that angle from :math:`x_1`.

        >>> ply = orthotropic(100, 3, 3, 10, 4, 10, 3, 5, 5)
        >>> back = ply.rotated(30).rotated(-30)
        >>> max(abs(a - b) for r, s in zip(back.matrix, ply.matrix) for a, b in zip(r, s)) < 1e-12
        True
        """
        angle = math.radians(float(as_real("ply angle", degrees)))
        if angle == 0:
            return self
        c, s = math.cos(angle), math.sin(angle)
        a = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        t = np.einsum("ip,jq,kr,ls,pqrs->ijkl", a, a, a, a, _tensor(self.array()))
        return Stiffness(tuple(map(tuple, _voigt(t))), self.kind)

    def with_loss(self, eta: float) -> Stiffness:
        """Hysteretic damping: :math:`C^* = C (1 - i \\eta)` with loss factor ``eta`` in
        [0, 1) (0 gives this law back). ``eta`` is about :math:`1/\\pi` times the
        attenuation in nepers per wavelength of each bulk wave.

        >>> isotropic(lam=1.0, mu=1.0).with_loss(0.01).matrix[3][3]
        (1-0.01j)
        """
        eta = float(as_real("loss factor eta", eta))
        if not 0 <= eta < 1:
            raise InputError(f"loss factor eta must lie in [0, 1), got {eta}")
        if eta == 0:
            return self
        if not self.lossless:
            raise InputError("with_loss: this stiffness is already damped")
        return Stiffness(tuple(map(tuple, self.array() * (1 - 1j * eta))), self.kind)

    def mirror_normal(self) -> bool:
        """True if the law is unchanged by :math:`x_3 \\to -x_3` (monoclinic about the
        plate's plane, as every orthotropic ply turned about the normal): a symmetric stack of
        such layers has symmetric and antisymmetric modes apart."""
        C = np.abs(self.array())
        return bool(np.max(C[np.ix_([0, 1, 2, 5], [3, 4])]) <= 1e-12 * np.max(C))

    def mirror_transverse(self) -> bool:
        """True if the law is unchanged by :math:`x_2 \\to -x_2`: waves along :math:`x_1`
        split into Lamb (:math:`u_1, u_3`) and shear-horizontal (:math:`u_2`) families."""
        C = np.abs(self.array())
        return bool(np.max(C[np.ix_([0, 1, 2, 4], [3, 5])]) <= 1e-12 * np.max(C))

    def is_isotropic(self, rtol: float = 1e-12) -> bool:
        """True if every rotation leaves the law unchanged (two constants, lambda and mu)."""
        C = self.array()
        lam, mu = C[0, 1], C[3, 3]
        iso = _isotropic_matrix(lam, mu)
        return bool(np.max(np.abs(C - iso)) <= rtol * np.max(np.abs(C)))

    def lame(self) -> tuple[float, float]:
        """``(lambda, mu)`` of an isotropic law (:class:`InputError` otherwise)."""
        if not (self.is_isotropic() and self.lossless):
            raise InputError(f"{self.describe()} is not an undamped isotropic law")
        return float(self.matrix[0][1]), float(self.matrix[3][3])

    def plane_strain_law(self):
        """The plane-strain law of the :math:`x_1 x_3` plane (the plate patch's x along and
        y through the thickness): :class:`~dispersion.materials.elastic_law.Orthotropic` with
        C11, C33, C13, C55, exact rationals of the floats.

        >>> isotropic(lam=2.0, mu=1.0).plane_strain_law().moduli()["D11"]
        4
        """
        from dispersion.materials.elastic_law import Orthotropic

        if not (self.lossless and self.mirror_transverse()):
            raise InputError("the plane-strain law needs an undamped stiffness whose x1-x3 "
                             "plane is a plane of symmetry")
        C = self.matrix
        return Orthotropic(C[0][0], C[2][2], C[0][2], C[4][4])

    # ------------------------------------------------------------------ words

    def describe(self) -> str:
        """The law in words (GPa, the non-zero upper entries)."""
        C = self.array()
        entries = [f"C{a + 1}{b + 1} {_gpa(C[a, b])}" for a in range(6) for b in range(a, 6)
                   if abs(C[a, b]) > 1e-9 * np.max(np.abs(C))]
        return f"{self.kind} ({', '.join(entries)} GPa)"

    def as_dict(self) -> dict:
        """JSON-ready: ``kind`` and ``C [GPa]`` (complex entries as ``[re, im]``)."""
        return {"kind": self.kind, "C [GPa]": [[v / 1e9 if isinstance(v, float)
                                               else [v.real / 1e9, v.imag / 1e9] for v in row]
                                              for row in self.matrix]}


def _gpa(value) -> str:
    if isinstance(value, complex) or np.iscomplexobj(value) and value.imag != 0:
        return f"({value.real / 1e9:.4g}{value.imag / 1e9:+.4g}i)"
    return f"{float(np.real(value)) / 1e9:.4g}"


def _isotropic_matrix(lam, mu) -> np.ndarray:
    C = np.zeros((6, 6), dtype=np.result_type(lam, mu, float))
    C[:3, :3] = lam
    for a in range(3):
        C[a, a] = lam + 2 * mu
        C[a + 3, a + 3] = mu
    return C


def isotropic(*, E=None, nu=None, lam=None, mu=None) -> Stiffness:
    """An isotropic law from (E, nu) or from the Lame constants (lam, mu), in Pa.

    >>> isotropic(E=200e9, nu=0.25).matrix[3][3] / 1e9
    80.0
    """
    if E is not None and nu is not None and lam is None and mu is None:
        E = check_positive("E", E)
        nu = float(as_real("nu", nu))
        if not -1 < nu < 0.5:
            raise InputError(f"nu must lie in (-1, 0.5), got {nu}")
        mu = E / (2 * (1 + nu))
        lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    elif lam is not None and mu is not None and E is None and nu is None:
        lam, mu = float(as_real("lambda", lam)), check_positive("mu", mu)
    else:
        raise InputError("isotropic: give (E, nu) or (lam, mu)")
    return Stiffness(tuple(map(tuple, _isotropic_matrix(float(lam), float(mu)))), "isotropic")


def from_speeds(c_L: float, c_T: float, rho: float) -> Stiffness:
    """An isotropic law from the bulk speeds (m/s) and the density (kg/m^3):
    :math:`\\mu = \\rho c_T^2`, :math:`\\lambda = \\rho (c_L^2 - 2 c_T^2)`.

    >>> from_speeds(2.0, 1.0, 1.0).matrix[0][:2]
    (4.0, 2.0)
    """
    c_L, c_T, rho = (check_positive(n, v) for n, v in (("c_L", c_L), ("c_T", c_T), ("rho", rho)))
    return isotropic(lam=rho * (c_L**2 - 2 * c_T**2), mu=rho * c_T**2)


def orthotropic(C11, C12, C13, C22, C23, C33, C44, C55, C66) -> Stiffness:
    """An orthotropic law with axes of symmetry :math:`x_1, x_2, x_3` from its nine
    stiffnesses (Pa)."""
    v = [float(as_real(n, x)) for n, x in zip(
        ("C11", "C12", "C13", "C22", "C23", "C33", "C44", "C55", "C66"),
        (C11, C12, C13, C22, C23, C33, C44, C55, C66))]
    C = np.zeros((6, 6))
    C[0, 0], C[0, 1], C[0, 2], C[1, 1], C[1, 2], C[2, 2], C[3, 3], C[4, 4], C[5, 5] = v
    C = np.triu(C) + np.triu(C, 1).T
    return Stiffness(tuple(map(tuple, C)), "orthotropic")


def transversely_isotropic(*, E1, E2, G12, nu12, nu23) -> Stiffness:
    """A unidirectional ply (fibres along :math:`x_1`, isotropic in the :math:`x_2 x_3`
    plane) from its engineering constants (Pa): the compliance inverted,

    .. math::

        S = \\begin{bmatrix} 1/E_1 & -\\nu_{12}/E_1 & -\\nu_{12}/E_1 \\\\
        & 1/E_2 & -\\nu_{23}/E_2 \\\\ & & 1/E_2 \\end{bmatrix}, \\quad
        S_{44} = 2(1 + \\nu_{23})/E_2, \\quad S_{55} = S_{66} = 1/G_{12}.

    >>> ply = transversely_isotropic(E1=142e9, E2=10.3e9, G12=7.2e9, nu12=0.27, nu23=0.54)
    >>> round(ply.matrix[3][3] / 1e9, 3)           # G23 = E2 / (2 (1 + nu23))
    3.344
    """
    E1, E2, G12 = (check_positive(n, v) for n, v in (("E1", E1), ("E2", E2), ("G12", G12)))
    nu12, nu23 = float(as_real("nu12", nu12)), float(as_real("nu23", nu23))
    S = np.zeros((6, 6))
    S[0, 0], S[1, 1], S[2, 2] = 1 / E1, 1 / E2, 1 / E2
    S[0, 1] = S[1, 0] = S[0, 2] = S[2, 0] = -nu12 / E1
    S[1, 2] = S[2, 1] = -nu23 / E2
    S[3, 3], S[4, 4], S[5, 5] = 2 * (1 + nu23) / E2, 1 / G12, 1 / G12
    if not np.linalg.eigvalsh(S)[0] > 0:
        raise InputError("transversely isotropic constants must give a positive definite "
                         f"compliance, got E1={E1:g}, E2={E2:g}, G12={G12:g}, nu12={nu12}, "
                         f"nu23={nu23}")
    C = np.linalg.inv(S)
    return Stiffness(tuple(map(tuple, (C + C.T) / 2)), "transversely isotropic")


def voigt(C, kind: str = "anisotropic") -> Stiffness:
    """Any symmetric positive definite 6x6 stiffness (Pa) in the Voigt order above."""
    return Stiffness(tuple(map(tuple, np.asarray(C))), kind)
