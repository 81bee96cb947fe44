"""A mode of a layered plate through the thickness: displacements, stresses, energy and its flow.

At a certified root :math:`(\\kappa, \\Omega)` of a class the null vector of the stack's
stiffness (:func:`~dispersion.continuum.layered.dynamic_stiffness.null_vector`) gives the
displacements :math:`U` at the sublayer faces; each face's traction
:math:`T = (\\sigma_{13}, \\sigma_{23}, \\sigma_{33})` follows from the sublayer stiffness
above it, and inside a sublayer the state :math:`\\xi = (U, T)` is carried by the exact
transfer matrix, :math:`\\xi(z + s) = e^{A s} \\xi(z)`
(:mod:`dispersion.continuum.layered.stroh`). The strains of
:math:`u = U(z) e^{i(\\kappa x_1 - \\Omega t)}` are
:math:`\\varepsilon_{11} = i\\kappa U_1`, :math:`2\\varepsilon_{12} = i\\kappa U_2`,
:math:`2\\varepsilon_{13} = U_1' + i\\kappa U_3`, :math:`2\\varepsilon_{23} = U_2'`,
:math:`\\varepsilon_{33} = U_3'` (:math:`U' = A_{uu} U + A_{ut} T`), the stresses
:math:`\\sigma = C \\varepsilon` (the three of T among them, a check), and the time averages

.. math::

    e_{kin} = \\tfrac14 \\rho \\Omega^2 |U|^2, \\quad
    e_{str} = \\tfrac14 \\operatorname{Re}(\\bar\\varepsilon^T C \\varepsilon), \\quad
    P_i = -\\tfrac12 \\operatorname{Re}(\\sigma_{ij} \\bar v_j), \\quad v = -i\\Omega U.

Integrated over the thickness (Gauss-Legendre in every sublayer), the **energy velocity**
:math:`c_e = \\int P \\,dz / \\int (e_{kin} + e_{str})\\, dz` is a vector in the plate's
plane: along the wave it is the group velocity :math:`d\\Omega/d\\kappa` (Biot's theorem, a
test), across it it gives the **skew angle** :math:`\\psi = \\arctan(c_{e2} / c_{e1})`, by
which the energy of an anisotropic plate's wave leaves the wave's direction.

A **damped** plate (complex moduli, complex :math:`\\kappa` at a real :math:`\\Omega`) has
no group velocity; the same ratio, taken at :math:`x = 0` where the decaying wave's amplitude
is the mode's, is its energy velocity (Bernard, Lowe and Deschamps 2001), and the strain
energy :math:`\\tfrac14 \\operatorname{Re}(\\bar\\varepsilon^T C \\varepsilon)` keeps the
storage part of the moduli. As the loss vanishes it tends to the group velocity.

>>> from dispersion.continuum.layered.layered_plate import laminate
>>> from dispersion.materials.materials import ply
>>> s = mode_shape(laminate("[0/90]s", ply("T800/913"), 0.125, direction=30), 1.0, "A0")
>>> round(s.skew_degrees, 6) != 0.0, s.u.shape[0]
(True, 3)

References
----------
B. A. Auld, *Acoustic fields and waves in solids*, vol. 1, 2nd ed., Krieger 1990, ch. 5
(Poynting's theorem, energy velocity); M. A. Biot, Phys. Rev. 105 (1957) 1129 (energy and
group velocity); A. Bernard, M. J. S. Lowe, M. Deschamps, "Guided waves energy velocity in
absorbing and non-absorbing plates", J. Acoust. Soc. Am. 110 (2001) 186; A. H. Nayfeh,
*Wave propagation in layered anisotropic media*, Elsevier 1995.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.continuum.layered.dynamic_stiffness import (_mid, _transfer, assemble,
                                                            element_stiffness, null_vector)
from dispersion.continuum.layered.stroh import system_matrix
from dispersion.errors import InputError

__all__ = ["LayeredModeShape", "mode_shape", "root_shape", "mode_fields", "energy_velocities",
           "skew_angles", "SAMPLES_PER_SUBLAYER", "GAUSS_PER_SUBLAYER"]

#: Points drawn in each sublayer (the ends included).
SAMPLES_PER_SUBLAYER = 9
#: Gauss-Legendre points of the thickness integrals in each sublayer. Rule: a sublayer is
#: thinner than half the shortest clamped wavelength and than 2 / kappa, so its fields are
#: smooth on it; 12 points integrate them to round-off (the Biot test measures it).
GAUSS_PER_SUBLAYER = 12


@dataclass(frozen=True)
class LayeredModeShape:
    """One mode through the thickness (units of the plate's
    :class:`~dispersion.continuum.layered.layered_plate.ScaledStack`: z over h, stresses over
    mu_ref, Omega over c_ref / h).

    ``z`` (n,) from the bottom face (-1) to the top (1); ``u`` (3, n) the displacement
    amplitudes :math:`U_1, U_2, U_3` (largest modulus 1, phase of the largest component 0);
    ``stress`` (6, n) in Voigt order (11, 22, 33, 23, 13, 12); ``kinetic``, ``strain`` (n,)
    the time-averaged energy densities; ``power`` (2,) the power through the thickness along
    and across the wave (per unit width); ``energy`` its integrated energy;
    ``energy_velocity`` (2,) along and across; ``group`` :math:`d\\Omega/d\\kappa` of the
    root (None for a damped plate, whose complex ``kappa`` has no group velocity);
    ``layer`` (n,) the layer (from the bottom, 0-based) each point lies in (a point on an
    interface appears twice, once in each layer); ``flow`` (2, n) the power flow density
    along and across the wave."""

    plate: object
    label: str
    kappa: complex
    omega: float
    z: np.ndarray
    u: np.ndarray
    stress: np.ndarray
    kinetic: np.ndarray
    strain: np.ndarray
    power: np.ndarray
    energy: float
    energy_velocity: np.ndarray
    group: float | None
    layer: np.ndarray
    flow: np.ndarray

    @property
    def skew_degrees(self) -> float:
        """The angle of the energy's flow from the wave's direction (degrees, positive
        towards the plate's +x2 side of the wave)."""
        return math.degrees(math.atan2(self.energy_velocity[1], self.energy_velocity[0]))


_E = np.eye(3)


def _strain_and_stress(C, rho, kappa, omega, xi):
    """Strain and stress (Voigt, (6, n)) of the states ``xi`` (6, n) of one layer."""
    A = system_matrix(C, rho, kappa, omega)
    d = A[:3, :] @ xi                     # U'
    U = xi[:3]
    ik = 1j * kappa
    eps = np.array([ik * U[0], np.zeros_like(U[0]), d[2], d[1], d[0] + ik * U[2], ik * U[1]])
    return eps, C @ eps


def mode_fields(stack, cls, elements, kappa: float, omega: float, samples: np.ndarray):
    """``(z, xi, layer)`` at the relative positions ``samples`` (in [0, 1]) of every sublayer:
    the state (6, n) of the class's mode at (kappa, Omega), unnormalised, for the class's
    stack (for a half class: from the mid-plane up)."""
    K = assemble(stack, cls, elements, kappa, omega, sparse=True)
    # undamped: K is Hermitian (its part, round-off off); damped: complex symmetric, as is
    v = null_vector((K + K.conj().T) / 2 if stack.lossless else K)
    chain, first, _ = _mid(stack, cls, elements)
    dofs = list(cls.dofs)
    sizes = [len(first)] + [len(dofs)] * len(chain)
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    nodes = []
    for j, comps in enumerate([first] + [dofs] * len(chain)):
        U = np.zeros(3, dtype=complex)
        U[list(comps)] = v[offsets[j]:offsets[j] + len(comps)]
        nodes.append(U)
    z0 = 0.0 if cls.half else -1.0
    zs, xis, layers = [], [], []
    cache = {}
    for j, (e, _) in enumerate(chain):
        if e.layer < 0:          # a spring: no thickness, the jump is between the nodes
            continue
        if e not in cache:
            cache[e] = element_stiffness(stack, e, np.array([kappa]), omega)[0]
        Ke = cache[e]
        U0, U1 = nodes[j], nodes[j + 1]
        T0 = -(Ke[:3, :3] @ U0 + Ke[:3, 3:] @ U1)      # traction on the sublayer's bottom face
        A = system_matrix(stack.C[e.layer], stack.rho[e.layer], np.array([kappa]), omega)[0]
        P = _transfer(np.broadcast_to(A, (samples.size, 6, 6)), samples * e.t)
        xis.append(P @ np.concatenate([U0, T0]))
        zs.append(z0 + samples * e.t)
        layers.append(np.full(samples.size, e.layer))
        z0 += e.t
    return np.concatenate(zs), np.concatenate(xis).T, np.concatenate(layers)


def _mirror(cls, z, xi, layer, n_layers: int):
    """The lower half of a symmetric class: components held on the mid-plane are odd in z
    (their tractions even), the others even (their tractions odd); the stack is its own
    mirror image, so each point below lies in a layer of the same law (layer n's mirror
    image is layer n_layers - 1 - n). With an even number of layers the mid-plane is an
    interface, sampled from both sides like every other."""
    odd = np.array([1.0 if d not in cls.mid_fixed else -1.0 for d in range(3)])
    sign = np.concatenate([odd, -odd])
    keep = z > 0 if n_layers % 2 else z >= 0
    return (np.concatenate([-z[keep][::-1] + 0.0, z]),
            np.concatenate([(xi[:, keep] * sign[:, None])[:, ::-1], xi], axis=1),
            np.concatenate([n_layers - 1 - layer[keep][::-1], layer]))


def _class_of(model, family: str, label: str):
    """The mode class that names ``label`` (its family, prefix and numbering)."""
    for name in model.classes():
        c = model.mode_class(name)
        rest = label[len(c.prefix):]
        if c.family == family and label.startswith(c.prefix) and rest.isdigit() \
                and (int(rest) - c.offset) % c.step == 0 and int(rest) >= c.offset:
            return c
    raise InputError(f"no mode class names {label!r}")


def _densities(stack, kappa, omega, xi, lay):
    """``(stress, kinetic, strain, p1, p2)`` at the states ``xi`` of layers ``lay``."""
    eps, sig = np.zeros((6, lay.size), complex), np.zeros((6, lay.size), complex)
    for L in np.unique(lay):
        at = lay == L
        eps[:, at], sig[:, at] = _strain_and_stress(stack.C[L], stack.rho[L], kappa, omega,
                                                    xi[:, at])
    kin = stack.rho[lay] * omega**2 * np.sum(np.abs(xi[:3]) ** 2, axis=0) / 4
    stra = np.real(np.einsum("in,in->n", eps.conj(),
                             np.einsum("nij,jn->in", stack.C[lay], eps))) / 4
    vbar = np.conj(-1j * omega * xi[:3])
    # sigma_1j and sigma_2j in Voigt: (11, 12, 13) and (12, 22, 23)
    p1 = -np.real(sig[0] * vbar[0] + sig[5] * vbar[1] + sig[4] * vbar[2]) / 2
    p2 = -np.real(sig[5] * vbar[0] + sig[1] * vbar[1] + sig[3] * vbar[2]) / 2
    return sig, kin, stra, p1, p2


def _flow(model, cls, kappa, omega: float):
    """``(power (2,), energy)`` through the thickness (Gauss-Legendre in every sublayer) of
    the unnormalised mode, and the sublayers used. A damped plate (complex ``kappa``): the
    time averages at x = 0, where the wave's amplitude is the mode's (Bernard, Lowe and
    Deschamps 2001); the strain energy takes the real part of the moduli (the imaginary
    part dissipates: :math:`\\bar\\varepsilon^T C'' \\varepsilon` is real, so
    :math:`\\operatorname{Re}(\\bar\\varepsilon^T C \\varepsilon)` is the stored part)."""
    stack = model.stack
    elements = model.elements(cls.name, omega, abs(kappa))
    g, w = np.polynomial.legendre.leggauss(GAUSS_PER_SUBLAYER)
    z, xi, lay = mode_fields(stack, cls, elements, kappa, omega, (g + 1) / 2)
    weights = np.concatenate([w / 2 * e.t for e, _ in _mid(stack, cls, elements)[0]
                              if e.layer >= 0])
    if cls.half:       # the lower half carries as much energy and power as the upper one
        weights = 2 * weights
    _, kin, stra, p1, p2 = _densities(stack, kappa, omega, xi, lay)
    return (np.array([np.sum(weights * p1), np.sum(weights * p2)]),
            float(np.sum(weights * (kin + stra))), elements)


def _wavenumber(k):
    """A root's kappa: real for an undamped plate, complex for a damped one."""
    k = complex(k)
    return k.real if k.imag == 0 else k


def energy_velocities(plate, roots) -> np.ndarray:
    """The energy velocity (n, 2) of every root of a
    :class:`~dispersion.continuum.layered.layered_modes.LayeredRoots` of an undamped
    ``plate`` or a :class:`~dispersion.continuum.layered.damped_modes.DampedRoots` of a
    damped one, along and across the waves (units of c_ref): power over energy through the
    thickness at x = 0, as :func:`mode_shape` gives it for one mode."""
    from dispersion.continuum.layered.layered_model import LayeredModel

    model = LayeredModel(plate)
    out = np.empty((len(roots.label), 2))
    for i, (lab, fam, k) in enumerate(zip(roots.label, roots.family, roots.kappa)):
        power, energy, _ = _flow(model, _class_of(model, fam, lab), _wavenumber(k),
                                 float(roots.omega[roots.index[i]]))
        out[i] = power / energy
    return out


def skew_angles(plate, roots) -> np.ndarray:
    """The skew angle (degrees) of every root of a
    :class:`~dispersion.continuum.layered.layered_modes.LayeredRoots` of ``plate``: 0 where
    the plate is decoupled along the direction (every layer symmetric about the plane of the
    wave and the normal: no power crosses it), else from the energy's flow."""
    if plate.decoupled:
        return np.zeros(len(roots.label))
    c_e = energy_velocities(plate, roots)
    return np.degrees(np.arctan2(c_e[:, 1], c_e[:, 0]))


def mode_shape(plate, omega: float, label: str) -> LayeredModeShape:
    """The mode ``label`` (as :func:`~dispersion.continuum.layered.layered_modes.layered_modes`
    names it) of ``plate`` at the dimensionless frequency ``omega``, through the thickness,
    with its energy velocity (see the module docstring); a damped plate's mode at its
    complex wavenumber (:func:`~dispersion.continuum.layered.damped_modes.damped_modes`)."""
    if plate.lossless:
        from dispersion.continuum.layered.layered_modes import layered_modes

        roots = layered_modes(plate, [omega])
    else:
        from dispersion.continuum.layered.damped_modes import damped_modes

        roots = damped_modes(plate, [omega])
    rows = [i for i, lab in enumerate(roots.label) if lab == label]
    if not rows:
        raise InputError(f"mode must be one of {', '.join(roots.label)} at Omega = {omega:g}; "
                         f"got {label!r}")
    return root_shape(plate, roots, rows[0])


def root_shape(plate, roots, i: int) -> LayeredModeShape:
    """The mode of root ``i`` of ``roots`` (a
    :class:`~dispersion.continuum.layered.layered_modes.LayeredRoots` or
    :class:`~dispersion.continuum.layered.damped_modes.DampedRoots` of ``plate``) through
    the thickness."""
    from dispersion.continuum.layered.layered_model import LayeredModel

    label, omega = roots.label[i], float(roots.omega[roots.index[i]])
    kappa = _wavenumber(roots.kappa[i])
    group = float(roots.group[i]) if hasattr(roots, "group") else None
    model = LayeredModel(plate)
    stack = model.stack
    cls = _class_of(model, roots.family[i], label)
    power, energy, elements = _flow(model, cls, kappa, omega)
    z, xi, lay = mode_fields(stack, cls, elements, kappa, omega,
                             np.linspace(0, 1, SAMPLES_PER_SUBLAYER))
    if cls.half:
        z, xi, lay = _mirror(cls, z, xi, lay, len(stack.rho))
    sig, kin, stra, p1, p2 = _densities(stack, kappa, omega, xi, lay)
    big = np.argmax(np.abs(xi[:3]).max(axis=1))
    norm = 1 / xi[big, np.argmax(np.abs(xi[big]))]     # largest component real and 1
    n2 = abs(norm) ** 2
    return LayeredModeShape(plate, label, kappa, omega, z, xi[:3] * norm, sig * norm,
                            kin * n2, stra * n2, power * n2, energy * n2, power / energy,
                            group, lay, np.array([p1, p2]) * n2)
