"""Isotropic materials: a small table with its sources, and materials given by the user.

A :class:`Material` is fixed by its bulk speeds :math:`c_L, c_T` (m/s) and, optionally, its
density :math:`\\rho` (kg/m^3); Poisson's ratio follows from the speeds,

.. math::

    \\nu = \\frac{c_L^2 - 2 c_T^2}{2 (c_L^2 - c_T^2)}, \\qquad
    c_T^2 = \\frac{E}{2\\rho(1+\\nu)}, \\quad c_L^2 = \\frac{E(1-\\nu)}{\\rho(1+\\nu)(1-2\\nu)},

so a material fixes :math:`\\nu` for a whole computation (:mod:`dispersion.answers.units` refuses
branches computed at another :math:`\\nu`). :func:`user_material` takes (E, nu, rho),
(c_L, c_T) or (c_L, c_T, rho) and refuses every other combination.

>>> m = material("steel")
>>> m.c_L, m.c_T, m.rho, round(m.nu, 4)
(5960.0, 3235.0, 7850.0, 0.2912)
>>> user_material(E=70e9, nu=0.33, rho=2700.0).name
'E = 70 GPa, nu = 0.33, rho = 2700 kg/m^3'

References
----------
CRC Handbook of Chemistry and Physics, section 14, "Speed of sound in various media", Table 1
(longitudinal and shear speeds of solids; the density column of its reproductions).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from dispersion.errors import InputError, as_real, check_positive

__all__ = [
    "ALUMINIUM",
    "MATERIALS",
    "PLIES",
    "Material",
    "material",
    "ply",
    "material_from_moduli",
    "user_material",
]

_CRC = 'CRC Handbook of Chemistry and Physics, sec. 14 "Speed of sound in various media", Table 1'


@dataclass(frozen=True)
class Material:
    """An isotropic material by its bulk wave speeds (m/s) and, optionally, density (kg/m^3).

    ``source`` says where the numbers come from (a handbook row, or the user's input).
    """

    c_L: float
    c_T: float
    rho: float | None = None
    name: str = "custom"
    source: str = "user input"

    def __post_init__(self):
        check_positive("c_T", self.c_T)
        check_positive("c_L", self.c_L)
        if self.rho is not None:
            check_positive("rho", self.rho)
        if not self.c_L > self.c_T * math.sqrt(4 / 3):  # nu > -1
            raise InputError(f"c_L must exceed c_T sqrt(4/3) (nu > -1), got c_L={self.c_L}, "
                             f"c_T={self.c_T}")

    @property
    def nu(self) -> float:
        """Poisson's ratio :math:`(c_L^2 - 2 c_T^2) / (2 (c_L^2 - c_T^2))`."""
        L2, T2 = self.c_L**2, self.c_T**2
        return (L2 - 2 * T2) / (2 * (L2 - T2))

    @property
    def nu_exact(self) -> Fraction:
        """:attr:`nu` in exact rational arithmetic from the speeds as stored (binary floats):
        the Poisson ratio the frequency calculator certifies its roots at. The float ``nu``
        is within an ulp or two of it, but next to a cut-off a root in kappa moves by
        :math:`1/(2\\delta)` times such a change (delta: the relative distance to the cut-off).

        >>> MATERIALS["steel"].nu_exact
        Fraction(291823, 1002255)
        """
        L2, T2 = Fraction(self.c_L) ** 2, Fraction(self.c_T) ** 2
        return (L2 - 2 * T2) / (2 * (L2 - T2))

    @property
    def plate_velocity(self) -> float:
        """S0 speed at :math:`fd \\to 0`: :math:`c_{pl} = 2 c_T \\sqrt{1 - c_T^2/c_L^2}` (m/s)."""
        return 2 * self.c_T * math.sqrt(1 - (self.c_T / self.c_L) ** 2)

    @property
    def shear_modulus(self) -> float | None:
        """:math:`\\mu = \\rho c_T^2` in Pa (None without a density)."""
        return None if self.rho is None else self.rho * self.c_T**2

    def describe(self) -> str:
        """The material in words with units, for headers and titles (its source: ``source``).

        >>> MATERIALS["steel"].describe()
        'steel (c_L 5960 m/s, c_T 3235 m/s, rho 7850 kg/m^3, nu 0.2912)'
        """
        rho = "" if self.rho is None else f", rho {self.rho:g} kg/m^3"
        return f"{self.name} (c_L {self.c_L:g} m/s, c_T {self.c_T:g} m/s{rho}, nu {self.nu:.4f})"

    def as_dict(self) -> dict:
        """Inputs as plain data (for CSV headers and JSON)."""
        return {"name": self.name, "c_L [m/s]": self.c_L, "c_T [m/s]": self.c_T,
                "rho [kg/m^3]": self.rho, "nu": self.nu, "source": self.source}

    def solid(self):
        """This material as a layer's :class:`~dispersion.materials.solid.Solid` (it needs a
        density); the solid remembers this material (``origin``)."""
        from dispersion.materials.solid import isotropic_solid

        if self.rho is None:
            raise InputError(f"material {self.name} has no density: a layer needs one "
                             "(give rho)")
        return isotropic_solid(self.c_L, self.c_T, self.rho, self.name, self.source, self)


def material_from_moduli(E: float, nu: float, rho: float, name: str | None = None) -> Material:
    """Material from Young's modulus E (Pa), Poisson's ratio and density (kg/m^3).

    >>> m = material_from_moduli(70e9, 0.33, 2700.0)
    >>> round(m.c_T), round(m.nu, 12)
    (3122, 0.33)
    """
    check_positive("E", E)
    check_positive("rho", rho)
    nu = as_real("nu", nu, "a finite real number in (-1, 0.5)")
    if not -1 < nu < 0.5:
        raise InputError(f"nu must lie in (-1, 0.5), got {nu}")
    c_T = math.sqrt(E / (2 * rho * (1 + nu)))
    c_L = math.sqrt(E * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu)))
    name = name or f"E = {E / 1e9:g} GPa, nu = {nu:g}, rho = {rho:g} kg/m^3"
    return Material(c_L, c_T, rho, name, "user input (E, nu, rho)")


#: The accepted combinations of :func:`user_material`, in the order they are tried.
USER_COMBINATIONS = (("E", "nu", "rho"), ("c_L", "c_T"), ("c_L", "c_T", "rho"))


def user_material(*, E=None, nu=None, rho=None, c_L=None, c_T=None,
                  name: str | None = None) -> Material:
    """A material from exactly one of (E, nu, rho), (c_L, c_T), (c_L, c_T, rho).

    E in Pa, rho in kg/m^3, speeds in m/s. Any other set of given values (too few, or more
    than one way to fix nu, such as c_L, c_T and nu) is refused with an
    :class:`~dispersion.errors.InputError` naming the values given.

    >>> user_material(c_L=6000.0, c_T=3000.0).nu
    0.3333333333333333
    >>> user_material(c_L=6000.0, c_T=3000.0, nu=0.3)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: material inputs (c_L, c_T, nu) do not form one of (E, nu, rho), (c_L, c_T), (c_L, c_T, rho): nu is fixed by the speeds alone
    """
    given = {k: v for k, v in (("c_L", c_L), ("c_T", c_T), ("E", E), ("nu", nu), ("rho", rho))
             if v is not None}
    names = tuple(given)
    if set(names) not in [set(c) for c in USER_COMBINATIONS]:
        combos = ", ".join(f"({', '.join(c)})" for c in USER_COMBINATIONS)
        why = ""
        if {"c_L", "c_T"} <= set(names) and ({"nu", "E"} & set(names)):
            why = ": nu is fixed by the speeds alone"
        elif {"E", "nu"} <= set(names) and {"c_L", "c_T"} & set(names):
            why = ": the speeds follow from E, nu and rho"
        raise InputError(f"material inputs ({', '.join(names) or 'none'}) do not form one of "
                         f"{combos}{why}")
    if rho is not None:
        _check_density(rho)
    if "E" in given:
        return material_from_moduli(E, nu, rho, name)
    label = name or (f"c_L = {c_L:g} m/s, c_T = {c_T:g} m/s"
                     + (f", rho = {rho:g} kg/m^3" if rho is not None else ""))
    return Material(float(as_real("c_L", c_L)), float(as_real("c_T", c_T)),
                    None if rho is None else float(as_real("rho", rho)), label,
                    f"user input ({', '.join(names)})")


def _check_density(rho) -> None:
    """Refuse a density no solid plate has (outside the plausible range of
    :data:`dispersion.materials.unit_mixups.PLAUSIBLE`, foams to osmium), naming the likely
    unit mix-up: 2.7 is aluminium's density in g/cm^3, not kg/m^3 (it gave c_L = 196 km/s).

    >>> _check_density(2.7)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: rho must lie in [100, 25000] kg/m^3 (solids, foams to osmium), got 2.7 kg/m^3: g/cm^3 given for kg/m^3? (2.7 g/cm^3 = 2700 kg/m^3)
    """
    from dispersion.materials.unit_mixups import PLAUSIBLE, unit_mixups

    lo, hi, unit = PLAUSIBLE["rho"]
    value = float(check_positive("rho", rho))
    if not lo <= value <= hi:
        hint = [h.split(": ", 1)[1] for h in unit_mixups(rho=value)]
        raise InputError(f"rho must lie in [{lo:g}, {hi:g}] {unit} (solids, foams to osmium), "
                         f"got {value:g} {unit}" + "".join(f": {h}" for h in hint))


def _row(name: str, c_L: float, c_T: float, rho: float, row: str) -> Material:
    return Material(c_L, c_T, rho, name, f'{_CRC}, row "{row}"')


#: The Dispersion Calculator's aluminium example (bulk speeds as issue 10 quotes them; the CRC
#: row "Duralumin 17S"), with the density of aluminium.
ALUMINIUM = _row("aluminium", 6320.0, 3130.0, 2700.0, "Duralumin 17S")

#: Common isotropic plates; speeds and density of the CRC handbook row named in ``source``.
MATERIALS: dict[str, Material] = {
    "aluminium": ALUMINIUM,
    "aluminium-rolled": _row("aluminium-rolled", 6420.0, 3040.0, 2700.0, "Aluminum, rolled"),
    "steel": _row("steel", 5960.0, 3235.0, 7850.0, "Steel, mild"),
    "stainless-steel": _row("stainless-steel", 5790.0, 3100.0, 7900.0, "Steel, 347 Stainless"),
    "copper": _row("copper", 5010.0, 2270.0, 8930.0, "Copper, rolled"),
    "brass": _row("brass", 4700.0, 2110.0, 8600.0, "Brass (70 Cu, 30 Zn)"),
    "titanium": _row("titanium", 6070.0, 3125.0, 4500.0, "Titanium"),
    "glass": _row("glass", 5640.0, 3280.0, 2320.0, "Glass, pyrex"),
    "pmma": _row("pmma", 2680.0, 1100.0, 1180.0, "Lucite"),
    "nickel": _row("nickel", 6040.0, 3000.0, 8900.0, "Nickel"),
    "magnesium": _row("magnesium", 5770.0, 3050.0, 1740.0, "Magnesium, annealed"),
    # the matrix of fibre composites and the usual adhesive (not a row of the CRC table)
    "epoxy": Material(2610.0, 1100.0, 1170.0, "epoxy",
                      "DISPERSE's material database (B. Pavlakovic, M. Lowe, DISPERSE user's "
                      "manual, Imperial College London), as listed by the Dispersion "
                      "Calculator (github.com/ArminHuber/Dispersion-Calculator, "
                      "Materials/MaterialList_Isotropic.txt, Epoxy_Disperse: E 3.941 GPa, "
                      "nu 0.392, rho 1170 kg/m^3, i.e. c_L 2610 m/s, c_T 1100 m/s)"),
}


def material(name: str) -> Material:
    """The table's material ``name`` (see :data:`MATERIALS`), else an InputError listing them.

    >>> material("unobtainium")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: material must be one of aluminium, aluminium-rolled, brass, copper, epoxy, glass, magnesium, nickel, pmma, stainless-steel, steel, titanium; got 'unobtainium'
    """
    key = str(name).strip().lower().replace("_", "-").replace(" ", "-")
    key = {"aluminum": "aluminium", "stainless": "stainless-steel", "plexiglass": "pmma",
           "acrylic": "pmma", "perspex": "pmma", "epoxy-resin": "epoxy"}.get(key, key)
    if key not in MATERIALS:
        raise InputError(f"material must be one of {', '.join(sorted(MATERIALS))}; got {name!r}")
    return MATERIALS[key]


def _plies() -> dict:
    """The fibre-composite plies (transversely isotropic, fibres along axis 1), built on
    first use (the isotropic table needs no numpy)."""
    from dispersion.materials.solid import Solid
    from dispersion.materials.stiffness import voigt

    from dispersion.materials.stiffness import transversely_isotropic

    def ti(c11, c12, c22, c23, c55):   # GPa; C13 = C12, C33 = C22, C44 = (C22 - C23)/2
        C = [[c11, c12, c12, 0, 0, 0], [c12, c22, c23, 0, 0, 0], [c12, c23, c22, 0, 0, 0],
             [0, 0, 0, (c22 - c23) / 2, 0, 0], [0, 0, 0, 0, c55, 0], [0, 0, 0, 0, 0, c55]]
        return voigt([[v * 1e9 for v in row] for row in C], "transversely isotropic")

    return {
        "T800/913": Solid(ti(154.0, 3.7, 9.5, 5.2, 4.2), 1550.0, "T800/913",
                          "A. M. A. Huber, M. G. R. Sause, JASA 144 (2018) 3236, "
                          "doi:10.1121/1.5082299 (CFRP ply, stiffness matrix as printed)"),
        "TVR380/M12R": Solid(transversely_isotropic(E1=46.43e9, E2=14.92e9, G12=5.233e9,
                                                    nu12=0.27, nu23=0.3), 1800.0,
                             "TVR380/M12R",
                             "the Dispersion Calculator's ply table (A. Huber, DLR; "
                             "github.com/ArminHuber/Dispersion-Calculator, Materials/"
                             "MaterialList_TransverselyIsotropic.txt, TVR380M12R_GFRP: rho "
                             "1800 kg/m^3, E1 46.43 GPa, E2 14.92 GPa, G12 5.233 GPa, "
                             "nu12 0.27, nu23 0.3; GFRP ply)"),
    }


#: Unidirectional fibre-composite plies by name (:func:`ply`); filled on first use.
PLIES: dict = {}


def ply(name: str):
    """The ply ``name`` of :data:`PLIES` (a :class:`~dispersion.materials.solid.Solid`),
    else an InputError listing them.

    >>> ply("t800/913").rho
    1550.0
    """
    if not PLIES:
        PLIES.update(_plies())
    key = {k.lower(): k for k in PLIES}.get(str(name).strip().lower())
    if key is None:
        raise InputError(f"ply must be one of {', '.join(sorted(PLIES))}; got {name!r}")
    return PLIES[key]
