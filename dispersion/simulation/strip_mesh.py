"""Stiffness, mass, load and stations of the strip: a tensor-product B-spline patch.

The strip :math:`[0, L] \\times [-H, H]` (H = 1, :math:`\\mu = \\rho = 1`, plane strain) carries
open uniform B-splines of degree p along x (:math:`N_x` elements of length b) and through the
thickness (:math:`n` control points, the thickness space of the plate patch,
:func:`dispersion.symbolic.plate.plate_patch` with the x-exact model). On a rectangle with a
constant material every matrix is a sum of Kronecker products of 1D Gram matrices
:math:`G^{ab}_{ij} = \\int N^{(a)}_i N^{(b)}_j dx` (x) and :math:`Y^{ab}` (y, the plate's
thickness matrices):

.. math::

    K_{xx} = (\\lambda + 2\\mu) G^{11} \\otimes Y^{00} + \\mu G^{00} \\otimes Y^{11}, \\quad
    K_{yy} = (\\lambda + 2\\mu) G^{00} \\otimes Y^{11} + \\mu G^{11} \\otimes Y^{00},

    K_{xy} = \\lambda G^{10} \\otimes Y^{01} + \\mu G^{01} \\otimes Y^{10}, \\qquad
    M = M_x \\otimes M_y ,

the mass being the rule's: its x-direction rule :math:`M_x` along the strip and the rule
itself through the thickness :math:`M_y` (with the redistribution of the singular rules), the
tensor product the plate patch of the dispersion analysis uses. DOFs are interleaved:
``2 * (i_x * n + j_y) + c`` for component c (0: x, 1: y), so the scalar mass solves both
components at once (``(n_points, 2)`` right-hand sides).

:math:`M_x` on :math:`N_x` elements comes from the registry (:func:`mass_matrix`) exactly on
short meshes and is extended by its interior row: the rule is asked on meshes of
:math:`m_0` and :math:`m_0 + 1, m_0 + 2` elements, and the extension of the first must give
the others exactly, else the rule is refused for the strip (its mass is not banded and
translation invariant inside: an exact build on thousands of elements is beyond reach).

The load is a traction on the end x = 0 with the burst's time history: along x over the
thickness (S0, symmetric) or along y (A0, antisymmetric), its nodal values
:math:`\\int N_j dy`. Stations (the plan's stations, then its phase stations) read u_x (S0)
or u_y (A0) on the mid-plane y = 0.

>>> from dispersion.simulation.strip import Strip, plan_strip
>>> mesh = strip_mesh(plan_strip(Strip(p=2, mass="consistent", travel=1, stations=2,
...                                    elements_per_wavelength=3)))
>>> mesh.K.shape == (2 * mesh.n_points, 2 * mesh.n_points), mesh.massless.size
(True, 0)
>>> round(float(mesh.mass.sum()), 9) == round(2 * mesh.plan.length, 9)   # rho * area
True

The strip is a :class:`~dispersion.discretization.finite_mesh.finite_patch.FinitePatch` (free ends) and
its matrices are the finite patch's one assembly
(:func:`~dispersion.discretization.finite_mesh.finite_assembly.assemble`); this module adds what the
simulation needs beside them: the load and the stations.

References
----------
T. J. R. Hughes, J. A. Cottrell, Y. Bazilevs, "Isogeometric analysis", CMAME 194 (2005)
4135-4195. L. Gao, V. M. Calo, "Fast isogeometric solvers for explicit dynamics", CMAME 274
(2014) 19-41 (Kronecker structure of tensor-product matrices). Paper eqs (1)-(4).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from dispersion.discretization.finite_mesh.direction_mass import grams as spline_grams
from dispersion.discretization.finite_mesh.direction_mass import x_mass
from dispersion.discretization.finite_mesh.finite_assembly import (BASES, KNOWN_STATES, check_rule,
                                                       explicit_step)

__all__ = ["StripMesh", "strip_mesh", "strip_patch", "spline_grams", "x_mass", "check_rule",
           "explicit_step", "KNOWN_STATES", "BASES"]


@dataclass(frozen=True, repr=False)
class StripMesh:
    """The assembled strip: ``K`` (2N x 2N CSR), the scalar mass ``mass`` (N x N CSR, N
    points; None where only its banded inverse ``mass_inverse`` is known), the ``massless``
    points (zero rows), the load (``load_dofs``, ``load_values``: unit traction) and the
    stations (``station_dofs``, ``station_weights``, one row each); ``patch`` and
    ``matrices`` the finite patch it is and its assembly."""

    plan: object
    rule: object
    K: sp.csr_matrix
    mass: sp.csr_matrix
    massless: np.ndarray
    load_dofs: np.ndarray
    load_values: np.ndarray
    station_dofs: np.ndarray
    station_weights: np.ndarray
    #: ``(stiffness, mass)`` of the rule's explicit step (:func:`explicit_step`).
    step_kind: tuple[str, str] = ("sparse", "solve")
    #: The banded inverse of the mass (a rule whose inverse mass is banded: no ``mass``).
    mass_inverse: sp.csr_matrix | None = None
    patch: object = None
    matrices: object = None

    @property
    def n_points(self) -> int:
        return self.K.shape[0] // 2

    @property
    def n_dofs(self) -> int:
        return self.K.shape[0]

    def __repr__(self) -> str:
        return (f"StripMesh({self.plan.strip.label()}: {self.n_dofs} DOFs, "
                f"{self.massless.size} massless points)")


def strip_patch(plan):
    """The finite patch of ``plan`` (:func:`dispersion.simulation.strip.plan_strip`): the
    strip with free ends, its x-mesh and thickness mesh, rule, contact set and nu."""
    from dispersion.discretization.finite_mesh.finite_patch import FinitePatch

    s = plan.strip
    return FinitePatch("strip", s.p, plan.n_elements_x, "free", s.mass, length=plan.length,
                       n=plan.n, nu=plan.nu, contact=s.contact, gamma_s=s.gamma_s,
                       h=plan.element_length)


def strip_mesh(plan) -> StripMesh:
    """Assemble the strip of ``plan`` (:func:`dispersion.simulation.strip.plan_strip`)."""
    from dispersion.discretization.finite_mesh.finite_assembly import assemble

    s = plan.strip
    patch = strip_patch(plan)
    m = assemble(patch, exact_x=True)  # the exact rule rounded once, as always
    n = plan.n
    comp = 0 if s.kind == "S" else 1
    load_dofs = 2 * np.arange(n) + comp  # the column x = 0: i_x = 0
    load_values = m.thickness["00"].sum(axis=1)  # int N_j dy (partition of unity)
    where = np.asarray(plan.stations + plan.phase_stations)  # the stations, then the phase ones
    ax, Nx = m.basis_x.evaluate(where)
    ay, Ny = m.basis_y.evaluate(np.zeros(1))
    station_dofs = 2 * (ax[:, :, None] * n + ay[0][None, None, :]).reshape(where.size, -1) + comp
    station_weights = (Nx[:, :, None] * Ny[0][None, None, :]).reshape(where.size, -1)
    return StripMesh(plan, m.rule, m.K, m.mass, m.massless, load_dofs, load_values,
                     station_dofs, station_weights, m.step_kind, m.mass_inverse, patch, m)
