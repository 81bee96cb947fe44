"""The front door: a plate patch with ``K``, ``M``, ``K_dyn``, its series and branches, and
the ring and bar problems, all with the toolkit's defaults (:mod:`dispersion.defaults`).

Everything here is re-exported by ``import dispersion`` (lazily: nothing heavy is imported
until used).

>>> import dispersion
>>> pt = dispersion.patch(mass="lumped")          # Bloch model, r = 2, p = 2, n = 3
>>> pt.K().shape, pt.M().is_diagonal()
((6, 6), True)
>>> dispersion.series("A0", 4, exact=True)[4]     # exact Rayleigh-Lamb, paper eq (15)
-2/(3*(nu - 1))

The matrices are those of the paper's eq (5) for one Bloch cell (or the x-exact strip),
scaled by the shear modulus and density:

.. math::

    \\mathbf K_{dyn}(\\kappa, \\Omega) = \\mathbf K(\\kappa) - \\Omega^2 \\mathbf M(\\kappa).

References
----------
A. Tkachuk, M. Matzen, R. Kolman, M. Bischoff, "Singular mass matrices for isogeometric
finite element analysis of dynamic contact", eqs (1)-(5), (14)-(20).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

from dispersion import defaults
from dispersion.errors import InputError

if TYPE_CHECKING:  # pragma: no cover
    import sympy

    from dispersion.symbolic.plate import PlatePatch

__all__ = ["Patch", "patch", "series", "exact_branches", "simulate_ring", "simulate_bar"]


@dataclass(frozen=True)
class Patch:
    """A plate patch of B-splines through the thickness with one mass variant.

    Build it with :func:`patch`. Parameters are those of :func:`dispersion.symbolic.plate.plate_patch`;
    ``plate`` is that exact object (built on first use).

    Attributes
    ----------
    p, n : int
        Degree and number of control points through the thickness.
    model : str
        ``"bloch"`` (one Bloch-periodic column, aspect ratio ``r = b/h``) or ``"x-exact"``.
    r : number, sympy expression
        Aspect ratio b/h of the Bloch model (``None`` for x-exact).
    mass : str
        ``"consistent"``, ``"lumped"``, ``"singular"`` or ``"singular-lumped"``.
    contact, gamma_s :
        Contact set and redistribution weight of the singular masses.
    """

    p: int = defaults.P
    n: int = defaults.N
    model: str = defaults.MODEL
    r: Any = defaults.R
    mass: str = defaults.MASS
    contact: str = defaults.CONTACT
    gamma_s: Any = defaults.GAMMA_S
    weights: Any = field(default=None, compare=False, repr=False)

    @cached_property
    def plate(self) -> PlatePatch:
        """The exact :class:`dispersion.symbolic.plate.PlatePatch` (validates every parameter)."""
        from dispersion.symbolic.plate import plate_patch

        return plate_patch(self.p, self.n, self.model, self.r, self.mass, self.contact,
                           self.gamma_s, self.weights)

    def K_dyn(self, kappa=None, Omega=None, nu=None) -> sympy.Matrix:
        """:math:`K - \\Omega^2 M` (sympy); symbols ``kappa``, ``Omega``, ``nu`` by default.

        Each value is a finite real number or a sympy expression with symbols; anything else
        (NaN, infinity, a string, a complex number) is an :class:`~dispersion.errors.InputError`.

        >>> patch().K_dyn(kappa=float("nan"))
        Traceback (most recent call last):
        ...
        dispersion.errors.InputError: kappa must be a finite real number or a sympy symbol, got nan
        """
        from dispersion.symbolic.plate import dynamic_stiffness

        return dynamic_stiffness(self.plate, _value("kappa", kappa), _value("Omega", Omega),
                                 _value("nu", nu))

    def K(self, kappa=None, nu=None) -> sympy.Matrix:
        """Stiffness :math:`K(\\kappa)` over the shear modulus (sympy)."""
        return self.K_dyn(kappa, 0, nu)

    def M(self, kappa=None) -> sympy.Matrix:
        """Mass :math:`M(\\kappa)` over the density (sympy): the variant of ``mass``.

        Every variant keeps the translational mass (the sum of all entries):

        >>> sum(patch(model="x-exact", mass="singular").M()) == sum(patch(model="x-exact").M())
        True
        """
        import sympy

        from dispersion.symbolic.plate import mass_block, x_functions

        kappa = sympy.Symbol("kappa") if kappa is None else sympy.sympify(_value("kappa", kappa))
        return x_functions(self.plate, kappa)["mx"] * mass_block(self.plate)

    def series(self, branch: str = "S0", order: int = 8, nu=None) -> dict[int, sympy.Expr]:
        """Taylor coefficients of :math:`\\Omega^2` in :math:`\\kappa` (eqs 17-20)."""
        from dispersion.symbolic.power_balance import discrete_series

        return discrete_series(branch, order, p=self.p, n=self.n, model=self.model, r=self.r,
                               mass=self.mass, contact=self.contact, gamma_s=self.gamma_s,
                               weights=self.weights, nu=nu)

    def branches(self, kappa, nu=defaults.NU_FLOAT):
        """All discrete branches on the grid ``kappa`` (:func:`dispersion.waves.discrete_branches.discrete_branches`)."""
        from dispersion.waves.discrete_branches import discrete_branches

        r = self.plate.r
        if r is not None and not getattr(r, "is_number", True):
            raise InputError(f"r must be a number > 0 for numeric branches, got the symbol {r}")
        return discrete_branches(self.plate, nu, kappa)


def _value(name: str, value):
    """``value`` of a patch matrix: None (the symbol), an expression with symbols, or a
    finite real number; anything else raises :class:`InputError` naming ``name``."""
    from dispersion.errors import as_real

    if value is None or getattr(value, "free_symbols", None):
        return value
    try:
        return as_real(name, value, "a finite real number or a sympy symbol")
    except InputError:
        raise
    except Exception:  # an object whose comparison or conversion fails
        raise InputError(f"{name} must be a finite real number or a sympy symbol, "
                         f"got {type(value).__name__}") from None


def patch(p: int = defaults.P, n: int = defaults.N, model: str = defaults.MODEL,
          r=defaults.R, mass: str = defaults.MASS, contact: str = defaults.CONTACT,
          gamma_s=defaults.GAMMA_S, weights=None) -> Patch:
    """A :class:`Patch`, checked at once (bad parameters raise :class:`InputError` here).

    ``r="r"`` keeps the aspect ratio symbolic. ``model="x-exact"`` ignores ``r``; giving
    one anyway is an error.

    >>> patch(mass="singular", gamma_s=0).plate.massless
    (2, 5)
    """
    import sympy

    if model == "x-exact" and r is not defaults.R and r is not None:
        raise InputError(f"r applies to the Bloch model only; model x-exact got r={r!r}")
    if model == "x-exact":
        r = None
    elif r == "r":
        r = sympy.Symbol("r", positive=True)
    pt = Patch(p, n, model, r, mass, contact, gamma_s, weights)
    pt.plate  # noqa: B018 - validate now, not on first use
    return pt


def series(branch: str = "S0", order: int = 8, *, exact: bool = False, nu=None,
           **patch_kwargs) -> dict[int, sympy.Expr]:
    """Series of the S0/A0 branch: exact Rayleigh-Lamb (``exact=True``, eqs 14-15) or of
    the discrete patch ``patch(**patch_kwargs)`` (eqs 17-20).

    >>> series("S0", 4, exact=True)[2]
    -2/(nu - 1)
    """
    if exact:
        if patch_kwargs:
            raise InputError(f"patch parameters {sorted(patch_kwargs)} do not apply with "
                             "exact=True (the exact Rayleigh-Lamb series)")
        from dispersion.waves.exact_series import exact_series

        return exact_series(branch, order, nu=nu)
    return patch(**patch_kwargs).series(branch, order, nu)


def exact_branches(kappa, nu=defaults.NU_FLOAT, omega_max: float = 8.0, **kwargs):
    """Exact Rayleigh-Lamb branches with :math:`\\Omega \\le` ``omega_max`` on ``kappa``
    (:func:`dispersion.waves.exact_branches.trace_branches`)."""
    from dispersion.waves.exact_branches import trace_branches

    return trace_branches(nu, kappa, omega_max, **kwargs)


def simulate_ring(mass: str = "singular", scheme: str = "kane", scenario=None, **changes):
    """The ring benchmark (Figure 4): :func:`dispersion.contact.simulate.simulate_ring` on
    ``scenario`` (default: the reconstructed :class:`~dispersion.contact.scenario.Scenario`)
    with fields replaced by ``changes`` (e.g. ``t_end=2.0``)."""
    from dataclasses import fields, replace

    from dispersion.contact.simulate import Scenario
    from dispersion.contact.simulate import simulate_ring as _simulate

    sc = scenario if scenario is not None else Scenario()
    unknown = sorted(set(changes) - {f.name for f in fields(sc)})
    if unknown:
        raise InputError(f"unknown scenario fields {unknown}; valid: "
                         f"{', '.join(f.name for f in fields(sc))}")
    return _simulate(replace(sc, **changes), mass, scheme)


def simulate_bar(n_elements: int = 40, p: int = defaults.P, mass: str = "lumped", **kwargs):
    """The 1-D bar impact (:func:`dispersion.contact.bar.simulate_bar`)."""
    from dispersion.contact.bar import simulate_bar as _simulate

    return _simulate(n_elements, p, mass, **kwargs)
