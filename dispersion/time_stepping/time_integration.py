"""The names of time integration, light enough for the command line to list them.

Two registries, each defined here once and read by the modules that compute with them:

- :data:`NEWMARK_MEMBERS`: the named members of Newmark's family as exact ``(beta, gamma)``
  (:func:`dispersion.time_stepping.fully_discrete.time_scheme` turns a name into a
  :class:`~dispersion.time_stepping.fully_discrete.TimeScheme`). ``"central"`` is the explicit
  central-difference scheme, the same member that contact problems call ``"central"``
  (:data:`dispersion.contact.newmark_scheme.CONTACT_SCHEMES`).
- :data:`CRITICAL_STEP_MODELS`: the discretizations whose critical step of central
  differences :func:`dispersion.time_stepping.timestep.critical_step` computes, with what each is.

Nothing here imports numpy or sympy: ``dispersion branches --help`` and a mistyped
``--scheme`` are answered without them.

>>> NEWMARK_MEMBERS["average-acceleration"]
(Fraction(1, 4), Fraction(1, 2))
>>> tuple(CRITICAL_STEP_MODELS)
('plate', 'bar')

References
----------
T. J. R. Hughes, *The Finite Element Method*, Dover 2000, sec. 9.3 (Newmark's method and its
members); N. M. Newmark, J. Eng. Mech. Div. ASCE 85 (1959) 67-94.
"""
from __future__ import annotations

from fractions import Fraction

__all__ = ["NEWMARK_MEMBERS", "CRITICAL_STEP_MODELS", "H_RANGE"]

#: Named Newmark members: name -> (beta, gamma), exact.
NEWMARK_MEMBERS = {
    "central": (Fraction(0), Fraction(1, 2)),
    "average-acceleration": (Fraction(1, 4), Fraction(1, 2)),
    "linear-acceleration": (Fraction(1, 6), Fraction(1, 2)),
    "fox-goodwin": (Fraction(1, 12), Fraction(1, 2)),
}

#: Models of the critical time step: name -> what it is (help texts and titles).
CRITICAL_STEP_MODELS = {
    "plate": "the Bloch plate patch with square elements (plane strain)",
    "bar": "the periodic 1D bar",
}

#: Element sizes h (m) of a critical step: the step 2 h / (c omega_max h/c) must be a normal
#: float for every wave speed of a solid (10 m/s to 100 km/s) and every omega_max h / c up to
#: 1e4; 1e-320 m made the consistent reference's step round to 0 (a division by zero).
H_RANGE = (1e-12, 1e12)
