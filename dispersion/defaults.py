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

>>> (P, N, MODEL, R, GAMMA_S)
(2, 3, 'bloch', 2, 1/2)
"""
from __future__ import annotations

import sympy

__all__ = ["P", "N", "MODEL", "R", "MASS", "CONTACT", "GAMMA_S", "NU", "NU_FLOAT", "FIGURE2_R"]

P = 2
N = 3
MODEL = "bloch"
R = 2
MASS = "consistent"
CONTACT = "top"
GAMMA_S = sympy.Rational(1, 2)
NU = sympy.Rational(3, 10)
NU_FLOAT = 0.3
#: Aspect ratio r = b/h of Figure 2's caption (h/b = 2).
FIGURE2_R = sympy.Rational(1, 2)
