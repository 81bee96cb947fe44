"""A finite patch as one value: the open (or periodic) mesh a user runs, not the lattice.

The analyses of the toolkit live on the infinite periodic lattice (the Bloch plate patch, the
periodic bar). A user's mesh is finite: with open knot vectors the B-splines next to a
boundary have short support and raise the largest frequencies above the lattice's (the
outliers of Cottrell, Reali, Bazilevs and Hughes 2006). A :class:`FinitePatch` says which
mesh:

* ``model``: ``"bar"`` (the 1D bar :math:`u_{,tt} = c^2 u_{,xx}` on :math:`[0, L]`, c = 1,
  so :math:`\\omega h / c` reads off directly) or ``"strip"`` (the plane-strain plate strip
  :math:`[0, L] \\times [-H, H]`, H = 1, :math:`\\mu = \\rho = 1`: lengths in H, frequencies
  in :math:`c_T / H`; the simulation's mesh);
* ``p``, ``n_elements`` (along x), ``n`` control points through the thickness (strip);
* ``ends``: each end ``"free"``, ``"fixed"`` (every DOF of the end column removed),
  ``"sliding"`` (strip: :math:`u_x = 0`, the shear traction free: the symmetry plane whose
  modes are the Rayleigh-Lamb modes at :math:`\\kappa = m \\pi H / L`) or both
  ``"periodic"`` (the lattice of N cells itself);
* ``knots``: ``"uniform"``, ``"graded"`` (element lengths in geometric progression, the last
  ``knot_parameter`` times the first) or ``"perturbed"`` (each interior knot moved by up to
  ``knot_parameter / 2`` of an element, uniformly at random from ``seed``);
* ``mass``: a rule of the registry (:data:`~dispersion.mass_rules.mass_rule.RULES`) with its
  boundary treatment: Galerkin masses lose the rows and columns of removed DOFs (the
  customized mass of approximate-dual lumping too: its banded inverse becomes the Schur
  complement, Hiemstra et al. 2025), the singular rules redistribute at the contact set (the
  strip's surfaces ``contact``; the bar's free ends) and their massless DOFs are condensed;
* ``removal``: an outlier-removal method (:mod:`dispersion.discretization.finite_mesh.outlier_removal`),
  ``removal_parameter`` its parameter;
* ``geometry``: a NURBS patch (``kv_xi``, ``kv_eta``, ``points``, ``weights``; the ring's
  quarter annulus, :func:`dispersion.splines.nurbs.quarter_ring`) mapping the strip
  (``model="strip"``, degree and knots the geometry's), with ``plane`` strain or stress.

A ``FinitePatch`` computes nothing; :func:`dispersion.discretization.finite_mesh.finite_assembly.assemble`
builds its K and M (sparse), :mod:`dispersion.discretization.finite_mesh.mesh_spectrum` its spectrum and
:mod:`dispersion.time_stepping.mesh_step` its stable step.

>>> finite_bar(2, 60, ends="free", mass="lumped").label()
'bar p=2 N=60 free-free, lumped mass'
>>> finite_strip(2, 10, ends=("fixed", "free"), n=4).ends
('fixed', 'free')

References
----------
J. A. Cottrell, A. Reali, Y. Bazilevs, T. J. R. Hughes, "Isogeometric analysis of structural
vibrations", CMAME 195 (2006) 5257-5296, doi:10.1016/j.cma.2005.09.027.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from fractions import Fraction

import numpy as np

from dispersion.defaults import MESH_ENDS
from dispersion.errors import InputError, check_choice, check_int_in_range, check_real_in_range

__all__ = ["MODELS", "ENDS", "KNOT_LAYOUTS", "MAX_MESH_DOFS", "P_MAX_MESH", "FinitePatch",
           "finite_bar", "finite_strip", "mapped_strip"]

MODELS = ("bar", "strip")
ENDS = MESH_ENDS
KNOT_LAYOUTS = ("uniform", "graded", "perturbed")
#: Highest degree of a finite patch. Rule: the float basis (Bernstein extraction from
#: Cox-de Boor samples) keeps its digits: the Bernstein matrix at p + 1 Chebyshev points has
#: a condition number below 1e3 up to p = 8 (measured, numpy.linalg.cond).
P_MAX_MESH = 8
#: Most DOFs of one finite patch (assembly and Lanczos in memory: about 1.5 GB at 2e6 DOFs
#: of the strip, measured 0.7 kB a DOF for K, M and the Lanczos vectors).
MAX_MESH_DOFS = 2_000_000
#: Largest knot grading (ratio of the last element to the first) and perturbation.
GRADING_RANGE = (1e-3, 1e3)
PERTURBATION_MAX = 0.9


def _ends(ends) -> tuple[str, str]:
    if isinstance(ends, str):
        ends = (ends, ends)
    if not isinstance(ends, (tuple, list)) or len(ends) != 2:
        raise InputError(f"ends must be one of {', '.join(ENDS)} or a pair of them, got {ends!r}")
    out = tuple(check_choice("ends", e, ENDS) for e in ends)
    if ("periodic" in out) and out != ("periodic", "periodic"):
        raise InputError(f"ends: a periodic end needs the other periodic too, got {out}")
    return out


@dataclass(frozen=True)
class FinitePatch:
    """The finite mesh of a bar or a plate strip (module docstring); build it with
    :func:`finite_bar`, :func:`finite_strip` or :func:`mapped_strip`."""

    model: str = "bar"
    p: int = 2
    n_elements: int = 20
    ends: tuple = ("free", "free")
    mass: str = "consistent"
    knots: str = "uniform"
    knot_parameter: float = 0.0
    seed: int = 0
    length: float = 1.0
    n: int | None = None
    nu: float = 0.3
    contact: str = "top"
    gamma_s: float = 0.5
    removal: str | None = None
    removal_parameter: float | None = None
    geometry: object = None
    plane: str = "strain"
    #: The element length of uniform knots, as the caller states it (None: length / N; a plan
    #: that computed both keeps its own rounding, so the assembly is the plan's to the bit).
    h: float | None = None

    def __post_init__(self):
        from dispersion.defaults import CONTACT_SETS
        from dispersion.mass_rules.mass_rule import get_rule

        set_ = object.__setattr__
        check_choice("model", self.model, MODELS)
        set_(self, "p", check_int_in_range("p", self.p, 1, P_MAX_MESH))
        set_(self, "ends", _ends(self.ends))
        lo = 2 * self.p + 1 if self.ends[0] == "periodic" else 1
        set_(self, "n_elements", check_int_in_range("n_elements", self.n_elements, lo,
                                                    MAX_MESH_DOFS))
        rule = get_rule(self.mass)
        set_(self, "mass", rule.name if isinstance(self.mass, str) else self.mass)
        check_choice("knots", self.knots, KNOT_LAYOUTS)
        if self.knots == "graded":
            set_(self, "knot_parameter", float(check_real_in_range(
                "knot_parameter (grading: last over first element)", self.knot_parameter,
                *GRADING_RANGE)))
        elif self.knots == "perturbed":
            set_(self, "knot_parameter", float(check_real_in_range(
                "knot_parameter (perturbation, fraction of an element)", self.knot_parameter,
                0.0, PERTURBATION_MAX)))
        if self.knots != "uniform" and self.ends[0] == "periodic":
            raise InputError("knots: a periodic patch has uniform knots (the lattice)")
        set_(self, "seed", check_int_in_range("seed", self.seed, 0, 2**32 - 1))
        set_(self, "length", float(check_real_in_range("length", self.length, 0, 1e9,
                                                        lo_open=True)))
        if self.h is not None:
            h = float(check_real_in_range("h (element length)", self.h, 0, 1e9, lo_open=True))
            if abs(h * self.n_elements - self.length) > 1e-9 * self.length:
                raise InputError(f"h must be length / n_elements = "
                                 f"{self.length / self.n_elements!r}, got {h!r}")
            set_(self, "h", h)
        set_(self, "nu", float(check_real_in_range("nu", self.nu, -1, 0.5, lo_open=True,
                                                    hi_open=True)))
        check_choice("contact", self.contact, CONTACT_SETS)
        set_(self, "gamma_s", float(check_real_in_range("gamma_s", self.gamma_s, 0, 1)))
        check_choice("plane", self.plane, ("strain", "stress"))
        if self.model == "bar":
            if self.n is not None:
                raise InputError("n (control points through the thickness) is a setting of "
                                 "the strip, not of the bar")
            if "sliding" in self.ends:
                raise InputError("ends: 'sliding' is a strip end (u_x = 0); the bar's ends are "
                                 "free, fixed or periodic")
            if self.geometry is not None:
                raise InputError("geometry maps a strip; the bar is straight")
        else:
            if self.geometry is not None:
                self._check_geometry()
            n = max(self.p + 1, 3) if self.n is None else self.n
            set_(self, "n", check_int_in_range("n (control points through the thickness)", n,
                                               self.p + 1, 200))
        from dispersion.discretization.finite_mesh.outlier_removal import check_removal

        check_removal(self)
        if self.n_dofs > MAX_MESH_DOFS:
            raise InputError(f"the patch has {self.n_dofs} DOFs; at most {MAX_MESH_DOFS} are "
                             "assembled (fewer elements or control points)")

    def _check_geometry(self) -> None:
        g = self.geometry
        if not all(hasattr(g, k) for k in ("kv_xi", "kv_eta", "points", "weights")):
            raise InputError("geometry must be a NURBS patch with kv_xi, kv_eta, points and "
                             "weights")
        if self.knots != "uniform" or self.ends[0] == "periodic":
            raise InputError("a mapped patch takes its knots from its geometry (uniform here) "
                             "and has open ends")
        if g.kv_xi.p != self.p or g.kv_eta.p != self.p:
            raise InputError(f"p must be the geometry's degree {g.kv_xi.p}, got {self.p}")
        if len(g.kv_xi.elements()) != self.n_elements or g.kv_eta.n != self.n:
            raise InputError("n_elements and n must be the geometry's (mapped_strip sets them)")

    # ------------------------------------------------------------------ derived numbers
    @property
    def periodic(self) -> bool:
        return self.ends[0] == "periodic"

    @property
    def mapped(self) -> bool:
        return self.geometry is not None

    @property
    def rule(self):
        from dispersion.mass_rules.mass_rule import get_rule

        return get_rule(self.mass)

    @property
    def dofs_per_point(self) -> int:
        return 1 if self.model == "bar" else 2

    @property
    def n_x(self) -> int:
        """Functions along x: N + p open, N periodic (N p + 1 for C0 Lagrange elements)."""
        if self.rule.basis == "lagrange":
            return self.n_elements * self.p + (0 if self.periodic else 1)
        return self.n_elements + (0 if self.periodic else self.p)

    @property
    def n_points(self) -> int:
        return self.n_x * (1 if self.model == "bar" else self.n)

    @property
    def n_dofs(self) -> int:
        return self.n_points * self.dofs_per_point

    @property
    def element_length(self) -> float:
        """The mean element length h = L / N (the element length of uniform knots)."""
        return self.length / self.n_elements if self.h is None else self.h

    def exact_knots(self) -> tuple[Fraction, ...]:
        """The open knot vector along x as exact rationals (the float knots are these)."""
        N, p = self.n_elements, self.p
        L = Fraction(self.length).limit_denominator(10**9)
        if self.knots == "uniform":
            inner = [L * i / N for i in range(1, N)]
        elif self.knots == "graded":
            q = self.knot_parameter ** (1.0 / (N - 1)) if N > 1 else 1.0
            sizes = q ** np.arange(N)
            x = np.cumsum(sizes)[:-1] / sizes.sum()
            inner = [L * Fraction(float(v)).limit_denominator(10**9) for v in x]
        else:
            rng = np.random.default_rng(self.seed)
            move = rng.uniform(-0.5, 0.5, N - 1) * self.knot_parameter
            inner = [L * Fraction(float((i + 1 + m) / N)).limit_denominator(10**9)
                     for i, m in enumerate(move)]
        return tuple([Fraction(0)] * (p + 1) + inner + [L] * (p + 1))

    def float_knots(self) -> np.ndarray:
        return np.array([float(k) for k in self.exact_knots()])

    def replace(self, **changes) -> FinitePatch:
        return replace(self, **changes)

    # ------------------------------------------------------------------ words
    def label(self) -> str:
        """One line naming the patch, rendered from the fields."""
        ends = "periodic" if self.periodic else "-".join(self.ends)
        size = f"N={self.n_elements}" + (f" n={self.n}" if self.model == "strip" else "")
        knots = "" if self.knots == "uniform" else f", {self.knots} knots ({self.knot_parameter:g})"
        where = "mapped strip" if self.mapped else self.model
        removal = "" if self.removal is None else f", {self.removal} removal"
        singular = (f" ({self.contact}, gamma_s={self.gamma_s:g})"
                    if self.rule.redistributes and self.model == "strip" else
                    f" (gamma_s={self.gamma_s:g})" if self.rule.redistributes else "")
        return (f"{where} p={self.p} {size} {ends}{knots}, {self.rule.name} mass{singular}"
                f"{removal}")

    def frequency_unit(self) -> str:
        """What the frequencies of this patch are measured in."""
        return "omega h / c" if self.model == "bar" else "omega H / c_T"


def finite_bar(p: int = 2, n_elements: int = 20, *, ends="free", mass="consistent",
               knots: str = "uniform", knot_parameter: float = 0.0, seed: int = 0,
               length: float = 1.0, gamma_s: float = 0.5, removal: str | None = None,
               removal_parameter: float | None = None) -> FinitePatch:
    """The 1D bar of ``n_elements`` elements on ``[0, length]`` (c = 1)."""
    return FinitePatch("bar", p, n_elements, ends, mass, knots, knot_parameter, seed, length,
                       None, 0.3, "top", gamma_s, removal, removal_parameter)


def finite_strip(p: int = 2, n_elements: int = 20, *, n: int | None = None, ends="free",
                 mass="consistent", length: float | None = None, nu: float = 0.3,
                 knots: str = "uniform", knot_parameter: float = 0.0, seed: int = 0,
                 contact: str = "top", gamma_s: float = 0.5, removal: str | None = None,
                 removal_parameter: float | None = None) -> FinitePatch:
    """The plane-strain strip of ``n_elements`` elements along x and ``n`` control points
    through the thickness 2H (H = 1); ``length`` defaults to square elements, b = 2H/(n - p)."""
    if length is None:
        nn = max(p + 1, 3) if n is None else n
        length = float(n_elements) * 2.0 / max(nn - p, 1)
    return FinitePatch("strip", p, n_elements, ends, mass, knots, knot_parameter, seed, length,
                       n, nu, contact, gamma_s, removal, removal_parameter)


def mapped_strip(geometry, *, mass="consistent", ends="free", nu: float = 0.3,
                 plane: str = "strain", contact: str = "top", gamma_s: float = 0.5,
                 removal: str | None = None) -> FinitePatch:
    """The strip mapped by the NURBS ``geometry`` (xi along, eta through the thickness; the
    ring's quarter annulus: ``contact="top"`` is its outer surface eta = 1)."""
    p = int(geometry.kv_xi.p)
    arc = _arc_length(geometry)
    return FinitePatch("strip", p, len(geometry.kv_xi.elements()), ends, mass, "uniform", 0.0,
                       0, arc, int(geometry.kv_eta.n), nu, contact, gamma_s, removal, None,
                       geometry, plane)


def _arc_length(geometry) -> float:
    """Length of the mid-surface eta = 1/2 (the mapped strip's length, for its labels)."""
    pts = np.asarray(geometry.points, float).reshape(geometry.kv_xi.n, geometry.kv_eta.n, 2)
    mid = pts[:, pts.shape[1] // 2]
    return float(max(np.sum(np.hypot(*np.diff(mid, axis=0).T)), math.ulp(1.0)))
