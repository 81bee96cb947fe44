"""The plate's elastic law: its plane-strain stiffness D over the shear modulus.

The plate patch (:mod:`dispersion.symbolic.plate`) needs four numbers of its material: the
plane-strain constitutive matrix in Voigt order (xx, yy, xy; x along the plate, y through the
thickness), scaled by the in-plane shear modulus :math:`D_{66}`,

.. math::

    \\sigma = D \\varepsilon, \\qquad
    \\frac{D}{D_{66}} = \\begin{bmatrix} D_{11} & D_{12} & 0 \\\\ D_{12} & D_{22} & 0 \\\\
        0 & 0 & D_{66} \\end{bmatrix} \\Big/ D_{66},

so that the plate's units are :math:`h = 1`, :math:`D_{66} = 1`, :math:`\\rho = 1`
(:math:`\\Omega = \\omega h / c_T`, :math:`c_T = \\sqrt{D_{66}/\\rho}`). An
:class:`ElasticLaw` is a value that gives them: exact (:meth:`~ElasticLaw.moduli`, where
Poisson's ratio may stay a symbol), in floats for the numeric pencil
(:meth:`~ElasticLaw.float_moduli`), as exact rationals of that float data
(:meth:`~ElasticLaw.rational_moduli`) and as polynomials of the series ring
(:meth:`~ElasticLaw.series_moduli`). The plate and everything that computes on it take the
law inside the patch (:attr:`dispersion.symbolic.patch.Patch.law`), so a new material is a
new value, not a change to the numerics.

* :class:`Isotropic`: Poisson's ratio nu (a number, or None: the symbol nu);
  :math:`D_{11} = D_{22} = \\lambda + 2\\mu`, :math:`D_{12} = \\lambda`, :math:`D_{66} = \\mu`
  (:func:`lame`).
* :class:`Orthotropic`: the stiffnesses :math:`C_{11}, C_{22}, C_{12}, C_{66}` of a material
  whose axes of symmetry are x and y. Under plane strain (:math:`\\varepsilon_{zz} = 0`) the
  in-plane block of the 3-D stiffness is D itself.

Only an isotropic plate has the closed-form Rayleigh-Lamb equation: the exact routes read
Poisson's ratio by :meth:`ElasticLaw.poisson_ratio`, which refuses every other law with an
:class:`~dispersion.errors.InputError` naming the route.

>>> Isotropic(0.25).float_moduli()
{'D11': 3.0, 'D22': 3.0, 'D12': 1.0, 'D66': 1.0}
>>> Orthotropic(165.7, 165.7, 63.9, 79.6).moduli()["D12"]       # silicon, <100> axes, GPa
639/796
>>> Orthotropic(165.7, 165.7, 63.9, 79.6).poisson_ratio("exact Rayleigh-Lamb branches")
Traceback (most recent call last):
...
dispersion.errors.InputError: the exact Rayleigh-Lamb branches need an isotropic plate (a closed form in Poisson's ratio); this plate is orthotropic (C11 = 1657/10, C22 = 1657/10, C12 = 639/10, C66 = 398/5): use the discrete routes

References
----------
R. M. Jones, *Mechanics of composite materials*, 2nd ed., 1999, section 2.2 (orthotropic
stiffness, positive definiteness); A. Tkachuk et al., section 2 (the plate in plane strain).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from dispersion.errors import InputError, check_nu

__all__ = ["ElasticLaw", "Isotropic", "Orthotropic", "MODULI", "as_law", "lame"]

#: The entries of D/D66 the plate uses, in Voigt notation (1 = xx, 2 = yy, 6 = xy).
MODULI = ("D11", "D22", "D12", "D66")


def lame(nu, scaled: bool = False) -> dict[str, object]:
    """Lame constants over :math:`\\mu` in plane strain: ``{"L": lambda, "M": mu, "L2M": lambda + 2 mu}``.

    ``scaled=True`` gives them times :math:`1 - 2\\nu` (polynomials in nu: ``2 nu``,
    ``1 - 2 nu``, ``2 (1 - nu)``), for exact polynomial arithmetic in any ring holding nu.

    >>> import sympy
    >>> lame(sympy.Rational(1, 4))
    {'L': 1, 'M': 1, 'L2M': 3}
    >>> lame(sympy.Symbol("nu"), scaled=True)["L2M"]
    2 - 2*nu
    """
    poly = {"L": 2 * nu, "M": 1 - 2 * nu, "L2M": 2 - 2 * nu}
    if scaled:
        return poly
    import sympy

    lam = 2 * nu / (1 - 2 * nu)
    return {"L": lam, "M": sympy.Integer(1) if isinstance(nu, sympy.Basic) else 1.0,
            "L2M": lam + 2}


def _isotropic_moduli(lam: dict) -> dict:
    """:func:`lame` as the entries of D/D66."""
    return {"D11": lam["L2M"], "D22": lam["L2M"], "D12": lam["L"], "D66": lam["M"]}


class ElasticLaw:
    """The interface of an elastic law of the plate (module docstring); a frozen value.

    A law states its own validity when it is made; every method below returns the entries
    :data:`MODULI` of :math:`D / D_{66}` in the arithmetic a route needs.
    """

    #: Short name of the kind of law (``"isotropic"``, ``"orthotropic"``).
    kind = "law"

    @property
    def numeric(self) -> bool:
        """True if every constant is a number (the numeric routes need it)."""
        raise NotImplementedError

    def moduli(self) -> dict[str, Any]:
        """Exact entries (sympy; symbols where the law keeps them)."""
        raise NotImplementedError

    def float_moduli(self) -> dict[str, float]:
        """Entries in floats, for the float pencil; :class:`InputError` if symbolic."""
        raise NotImplementedError

    def exact(self) -> ElasticLaw:
        """The law of the data the float routes use, in exact rationals (a float nu by its
        shortest decimal, as a float route sees it); :class:`InputError` if symbolic."""
        raise NotImplementedError

    def rational_moduli(self) -> dict[str, Any]:
        """:meth:`moduli` of :meth:`exact` (sympy Rationals): the exact and ball-arithmetic
        twins of the float pencil use them."""
        return self.exact().moduli()

    #: Names of the symbols the series ring carries for this law (after ``w`` and before r).
    series_parameters: tuple[str, ...] = ()

    def series_moduli(self, gens: dict, one) -> tuple[dict, Any]:
        """``(entries, scale)`` in the series ring: polynomials in ``gens`` (name ->
        generator, :attr:`series_parameters`) that equal ``scale`` times :meth:`moduli`;
        ``one`` is the ring's unit. The mass is multiplied by the same ``scale``."""
        raise NotImplementedError

    def substitute(self, series: dict) -> dict:
        """A series ``{power: sympy expression}`` with this law's numbers put in for the
        symbols of :attr:`series_parameters` (unchanged where the law keeps them)."""
        return series

    def substitutions(self) -> dict:
        """``{name: number}`` for the symbols of :attr:`series_parameters` this law gives
        numbers for (what :meth:`substitute` puts in; the flint form takes them by
        :func:`dispersion.symbolic.power_balance.substitute_raw`)."""
        return {}

    def poisson_ratio(self, route: str) -> float:
        """Poisson's ratio of an isotropic plate with a numeric nu, for ``route`` (a closed
        form of the isotropic plate: the exact Rayleigh-Lamb branches, series, shapes);
        :class:`InputError` naming ``route`` for every other law."""
        raise InputError(f"the {route} need an isotropic plate (a closed form in Poisson's "
                         f"ratio); this plate is {self.describe()}: use the discrete routes")

    def check_numeric(self, route: str) -> ElasticLaw:
        """``self`` if :attr:`numeric`, else :class:`InputError` naming ``route``."""
        if not self.numeric:
            raise InputError(f"the {route} need numbers: {self.describe()} is symbolic; "
                             "give the patch a number (e.g. nu=0.3)")
        return self

    # ------------------------------------------------------------------ words

    def describe(self) -> str:
        """The law in words, with its constants."""
        raise NotImplementedError

    def label(self) -> str | None:
        """Short text for a patch's label (None where nothing needs saying)."""
        raise NotImplementedError

    def title(self) -> str | None:
        """Text for a patch's title (None where nothing needs saying)."""
        raise NotImplementedError

    def header_lines(self) -> list[str]:
        """``key = value`` lines of the constants (for CSV ``#`` headers)."""
        raise NotImplementedError

    def as_dict(self) -> dict:
        """JSON-ready fields (exact numbers as strings), with ``"kind"``."""
        raise NotImplementedError

    @staticmethod
    def from_dict(data: dict) -> ElasticLaw:
        """Inverse of :meth:`as_dict`.

        >>> law = Orthotropic(3, 2, 1, 1)
        >>> ElasticLaw.from_dict(law.as_dict()) == law
        True
        """
        data = dict(data)
        kind = data.pop("kind", None)
        laws = {"isotropic": Isotropic, "orthotropic": Orthotropic}
        if kind not in laws:
            raise InputError(f"law kind must be one of {', '.join(laws)}; got {kind!r}")
        try:
            return laws[kind](**data)
        except TypeError as exc:
            raise InputError(f"law {kind}: {exc}") from None


def _exact(name: str, value):
    from dispersion.reader import rational

    return rational(name, value)


def _decimal(value):
    """The shortest decimal of ``float(value)`` as a sympy Rational: what a float route saw."""
    from dispersion.reader import rational

    return rational("value", float(value))


@dataclass(frozen=True)
class Isotropic(ElasticLaw):
    """An isotropic plate: Poisson's ratio ``nu`` in (-1, 1/2), a number (kept as given:
    a float, an int or a sympy Rational) or a sympy symbol; None is the symbol nu.

    >>> Isotropic().moduli()["D12"]
    2*nu/(1 - 2*nu)
    >>> Isotropic(0.3).rational_moduli()["D11"]
    7/2
    """

    nu: Any = None
    kind = "isotropic"

    def __post_init__(self):
        if self.nu is not None:
            check_nu(self.nu)

    @property
    def series_parameters(self) -> tuple[str, ...]:
        # the series is derived in nu and the number put in at the end (one derivation
        # serves every nu; factored as the symbolic one)
        return ("nu",)

    @property
    def numeric(self) -> bool:
        return self.nu is not None and not getattr(self.nu, "free_symbols", None)

    def _nu(self):
        import sympy

        return sympy.Symbol("nu") if self.nu is None else self.nu

    def moduli(self) -> dict[str, Any]:
        return _isotropic_moduli(lame(self._nu()))

    def float_moduli(self) -> dict[str, float]:
        self.check_numeric("float pencil")
        return _isotropic_moduli(lame(float(self.nu)))

    def exact(self) -> Isotropic:
        self.check_numeric("exact pencil")
        return Isotropic(_decimal(self.nu))

    def series_moduli(self, gens: dict, one) -> tuple[dict, Any]:
        nu = gens["nu"]
        return _isotropic_moduli(lame(nu, scaled=True)), 1 - 2 * nu

    def substitute(self, series: dict) -> dict:
        if self.nu is None:
            return series
        import sympy

        nu = sympy.Rational(repr(self.nu)) if isinstance(self.nu, float) else self.nu
        symbol = sympy.Symbol("nu")
        return {k: sympy.factor(v.subs(symbol, nu)) for k, v in series.items()}

    def substitutions(self) -> dict:
        return {} if self.nu is None else {"nu": self.nu}

    def poisson_ratio(self, route: str) -> float:
        self.check_numeric(route)
        return float(self.nu)

    def describe(self) -> str:
        return "isotropic (nu symbolic)" if self.nu is None else f"isotropic (nu = {self.nu})"

    def label(self) -> str | None:
        return None if self.nu is None else f"nu={self.nu}"

    def title(self) -> str | None:
        return None if self.nu is None else f"nu = {self.nu}"

    def header_lines(self) -> list[str]:
        return [] if self.nu is None else [f"nu = {self.nu}"]

    def as_dict(self) -> dict:
        return {"kind": self.kind, "nu": None if self.nu is None else str(self.nu)}


@dataclass(frozen=True)
class Orthotropic(ElasticLaw):
    """A plate of an orthotropic material with axes of symmetry x (along the plate) and y
    (through the thickness): its stiffnesses ``c11, c22, c12, c66`` in any one unit (GPa,
    say), exact rationals (floats by their shortest decimal).

    Valid: :math:`C_{66} > 0` and the plane-strain D positive definite,
    :math:`C_{11} > 0`, :math:`C_{22} > 0`, :math:`C_{12}^2 < C_{11} C_{22}`.

    >>> Orthotropic(1, 1, 2, 1)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: orthotropic stiffness must be positive definite (C11 > 0, C22 > 0, C12^2 < C11 C22), got C11 = 1, C22 = 1, C12 = 2
    """

    c11: Any
    c22: Any
    c12: Any
    c66: Any
    kind = "orthotropic"

    def __post_init__(self):
        values = {name: _exact(name.upper(), getattr(self, name))
                  for name in ("c11", "c22", "c12", "c66")}
        for name, v in values.items():
            object.__setattr__(self, name, v)
        if not values["c66"] > 0:
            raise InputError(f"shear stiffness C66 must be > 0, got {values['c66']}")
        c11, c22, c12 = values["c11"], values["c22"], values["c12"]
        if not (c11 > 0 and c22 > 0 and c12**2 < c11 * c22):
            raise InputError("orthotropic stiffness must be positive definite (C11 > 0, "
                             "C22 > 0, C12^2 < C11 C22), got "
                             f"C11 = {c11}, C22 = {c22}, C12 = {c12}")
        ratios = [abs(v / values["c66"]) for v in (c11, c22, c12) if v != 0]
        if any(not 1e-6 <= float(q) <= 1e6 for q in ratios):
            # beyond, the float pencil keeps no digit of the softer terms (as R_RANGE bounds
            # the aspect ratio)
            raise InputError("orthotropic stiffness ratios |C11|, |C22|, |C12| over C66 must "
                             f"lie in [1e-6, 1e6], got {', '.join(f'{float(q):.3g}' for q in ratios)}")

    @property
    def numeric(self) -> bool:
        return True

    def moduli(self) -> dict[str, Any]:
        import sympy

        return {"D11": self.c11 / self.c66, "D22": self.c22 / self.c66,
                "D12": self.c12 / self.c66, "D66": sympy.Integer(1)}

    def float_moduli(self) -> dict[str, float]:
        return {k: float(v) for k, v in self.moduli().items()}

    def exact(self) -> Orthotropic:
        return self

    def series_moduli(self, gens: dict, one) -> tuple[dict, Any]:
        import flint

        return ({k: one * flint.fmpq(int(v.p), int(v.q)) for k, v in self.moduli().items()},
                one)

    # ------------------------------------------------------------------ closed forms

    def extensional_modulus(self):
        """:math:`(C_{11} - C_{12}^2 / C_{22}) / C_{66}`: the plate's stretching stiffness
        with :math:`\\sigma_{yy} = 0`, over the shear modulus (exact)."""
        return (self.c11 - self.c12**2 / self.c22) / self.c66

    def describe(self) -> str:
        return (f"orthotropic (C11 = {self.c11}, C22 = {self.c22}, C12 = {self.c12}, "
                f"C66 = {self.c66})")

    def label(self) -> str | None:
        return (f"orthotropic C11:C22:C12:C66 = {self.c11}:{self.c22}:{self.c12}:"
                f"{self.c66}")

    def title(self) -> str | None:
        return self.describe()

    def header_lines(self) -> list[str]:
        return ["law = orthotropic"] + [f"{name.upper()} = {getattr(self, name)}"
                                        for name in ("c11", "c22", "c12", "c66")]

    def as_dict(self) -> dict:
        return {"kind": self.kind, **{name: str(getattr(self, name))
                                      for name in ("c11", "c22", "c12", "c66")}}


def as_law(value=None) -> ElasticLaw:
    """The law of ``value``: an :class:`ElasticLaw` as it is, else Poisson's ratio of an
    :class:`Isotropic` plate (None: nu symbolic). The front doors that take a bare ``nu``
    turn it into a law here, once.

    >>> as_law(0.3)
    Isotropic(nu=0.3)
    """
    if isinstance(value, ElasticLaw):
        return value
    return Isotropic(value)

