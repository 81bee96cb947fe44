"""The paper's redistribution matrix in floats, for the numeric contact scenes (no sympy, no scipy).

The exact matrix is :func:`dispersion.mass_rules.mass.redistribution_matrix`; this is the same
placement of the same weights (:func:`dispersion.mass_rules.mass.contact_weights`) as a numpy
array, so that a bar or a ring does not load sympy for it (tested equal).
"""
from __future__ import annotations

import numpy as np

from dispersion.errors import InputError
from dispersion.mass_rules.mass import contact_weights

__all__ = ["float_redistribution"]


def float_redistribution(n: int, contact: str, gamma_s: float) -> np.ndarray:
    """Float redistribution matrix of :func:`dispersion.mass_rules.mass.redistribution_matrix` across ``n``
    functions, contact set ``contact`` (``"top"``: index n-1, ``"bottom"``: index 0).

    >>> float_redistribution(3, "bottom", 0.5).tolist()
    [[0.0, 0.5, 0.5], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    """
    # the paper's weights (contact_weights: sympy-free) placed as redistribution_matrix
    # places them, in floats: a numeric scene does not load sympy (tested equal)
    weights = contact_weights(n, contact, gamma_s)
    for c, ws in weights.items():  # the exact matrix's rule: targets are non-contact points
        bad = [j for j in ws if j in weights or not (0 <= j < n)]
        if bad:
            raise InputError(f"weights of contact point {c} must target non-contact indices "
                             f"in [0, {n - 1}], got {bad}")
    R = np.eye(n)
    for c, ws in weights.items():
        R[c, c] = 0.0
        for j, w in ws.items():
            R[c, j] = float(w)
    return R
