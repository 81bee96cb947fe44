"""The toolkit's defaults, stated once and shared by the API, the CLI and the scenarios.

Every public function and every CLI option that takes one of these parameters uses the value
here as its default, so ``plate_patch()``, ``dispersion series`` and ``dispersion branches``
describe the same patch unless told otherwise.

- ``P = 2``, ``N = 3``: quadratic B-splines, three control points through the thickness
  (the paper's section 2).
- ``MODEL = "bloch"``, ``R = 2``: one Bloch-periodic column of square elements, b = 2h, the
  setting in which the derived series reproduce eqs (18) and (20). Figure 2's caption
  (h/b = 2) is ``R = 1/2``, passed explicitly where that figure is drawn.
- ``MASS = "consistent"``, ``CONTACT = "top"``.
- ``GAMMA_S = 1/2``: the paper's text ("equal redistribution with gamma_s = 0.5 is used
  everywhere below", Figure 1).
- ``NU = 3/10``: Poisson's ratio of the numeric results (the series keep nu symbolic).

>>> from dispersion import defaults as d
>>> (d.P, d.N, d.MODEL, d.R, d.GAMMA_S, d.GAMMA_S_FLOAT)
(2, 3, 'bloch', 2, 1/2, 0.5)

The exact values (sympy Rationals) are made on first use, so that a numeric command that
reads a default does not import sympy.
"""
from __future__ import annotations

__all__ = ["P", "N", "MODELS", "MODEL", "R", "MASS", "CONTACT", "GAMMA_S", "GAMMA_S_FLOAT", "NU",  # noqa: F822
           "NU_FLOAT", "FIGURE2_R"]  # GAMMA_S, NU, FIGURE2_R: module __getattr__

P = 2
N = 3
#: The patch models along x (``MODEL`` is one of them); stated here so that the command line
#: lists them without importing the symbolic patch.
MODELS = ("x-exact", "bloch")
MODEL = "bloch"
R = 2
MASS = "consistent"
CONTACT = "top"
#: The exact defaults as (numerator, denominator): GAMMA_S, NU and FIGURE2_R (the aspect ratio
#: r = b/h of Figure 2's caption, h/b = 2) are sympy Rationals made from these on first use.
_RATIONAL = {"GAMMA_S": (1, 2), "NU": (3, 10), "FIGURE2_R": (1, 2)}
GAMMA_S_FLOAT = _RATIONAL["GAMMA_S"][0] / _RATIONAL["GAMMA_S"][1]
NU_FLOAT = _RATIONAL["NU"][0] / _RATIONAL["NU"][1]


def text(name: str) -> str:
    """The default ``name`` as text (``"1/2"`` for GAMMA_S), without importing sympy.

    >>> text("GAMMA_S"), text("R")
    ('1/2', '2')
    """
    if name in _RATIONAL:
        p, q = _RATIONAL[name]
        return str(p) if q == 1 else f"{p}/{q}"
    return str(globals()[name])


def __getattr__(name: str):
    if name in _RATIONAL:
        import sympy

        value = sympy.Rational(*_RATIONAL[name])
        globals()[name] = value  # made once
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
