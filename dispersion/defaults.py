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

from fractions import Fraction

__all__ = ["P", "N", "PATCH_MODELS", "MODEL", "R", "MASS", "CONTACT", "GAMMA_S", "GAMMA_S_FLOAT", "NU",  # noqa: F822
           "NU_FLOAT", "FIGURE2_R", "CONTACT_SETS", "MESH_ENDS",
           "REPORT_OUT", "REPORT_REFERENCE", "MAX_JOBS_PER_CPU", "P_MAX", "N_MAX",
           "R_RANGE"]  # GAMMA_S, NU, FIGURE2_R: module __getattr__

P = 2
N = 3
#: The patch models along x (``MODEL`` is one of them): the registry that
#: :class:`dispersion.symbolic.patch.Patch` checks against, here so that the command line lists
#: them without importing the symbolic patch.
PATCH_MODELS = ("x-exact", "bloch")
MODEL = "bloch"
R = 2
MASS = "consistent"
CONTACT = "top"
#: ``dispersion reproduce``: where a user's run goes (untracked; listed in .gitignore) and the
#: committed reference it is compared with (:mod:`dispersion.report.run`).
REPORT_OUT = "reproduced"
REPORT_REFERENCE = "reports"
#: Most workers of :func:`dispersion.sweep.process_pool` per usable CPU. More only queue for
#: the cores while each holds its own copy of the toolkit in memory (about 150 MB); 4 leaves
#: room for workers that wait on I/O. :func:`dispersion.sweep.parallel_map` starts at most one
#: per usable CPU: its calls are CPU-bound sweeps.
MAX_JOBS_PER_CPU = 4
#: Most directions of one slowness-curve request (every mode solved at each;
#: :mod:`dispersion.answers.slowness_table`, ``--angle``).
MAX_ANGLES = 361
#: Contact sets of a singular mass through the thickness (:mod:`dispersion.mass_rules.mass`).
CONTACT_SETS = ("top", "bottom", "both")
#: The ends of a finite patch (:mod:`dispersion.discretization.finite_mesh.finite_patch`), here so that
#: the command line names them without importing numerics.
MESH_ENDS = ("free", "fixed", "sliding", "periodic")

# Limits of the plate patch (:mod:`dispersion.symbolic.plate` checks them; stated here so
# that the command line states its ranges without importing sympy).
#: Highest degree p through the thickness. The rule: the float pencil of the numeric branches
#: keeps digits. The thickness Gram matrix Y_00 of one element (n = p + 1) has condition
#: number 2.4e4 at p = 8, 1.2e9 at p = 16, 6.3e13 at p = 24 and 4.1e17 at p = 32 (measured,
#: numpy.linalg.cond): beyond p = 24 a float64 solve keeps no correct digit.
P_MAX = 24
#: Most control points n through the thickness. The rule: the patch builds in about a minute.
#: The singular mass is the dearest (sympy products of n x n matrices, growth n^3): p = 2,
#: n = 80 2.1 s, n = 160 16.5 s (measured on the busy 2-core machine), so n = 200 takes
#: about 30 s and n = 256 over a minute. Memory stays below 100 MiB.
N_MAX = 200
#: Valid aspect ratios r = b/h of the Bloch model, as exact fractions. Outside, the float
#: pencil of the numeric branches loses its digits (the d-function is a difference of O(1)
#: terms divided by r^2, and the S0 frequency at r = 1e-8 came out 100 % wrong), and exact
#: rationals grow huge (checked by :func:`dispersion.symbolic.patch.aspect_ratio`).
R_RANGE = (Fraction(1, 1000), Fraction(1000))
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
