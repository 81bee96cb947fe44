"""The paper's redistribution matrix in floats, for the numeric contact scenes (no sympy, no scipy).

The exact matrix is :func:`dispersion.symbolic.mass.redistribution_matrix`; this is the same
placement of the same weights (:func:`dispersion.symbolic.mass.contact_weights`) as a numpy
array, so that a bar or a ring does not load sympy for it (tested equal).
"""
from __future__ import annotations

import numpy as np

from dispersion.symbolic.mass import contact_weights

__all__ = ["float_redistribution"]


def float_redistribution(n: int, contact: str, gamma_s: float) -> np.ndarray:
    """Float redistribution matrix of :func:`dispersion.symbolic.mass.redistribution_matrix` across ``n``
    functions, contact set ``contact`` (``"top"``: index n-1, ``"bottom"``: index 0).

    >>> float_redistribution(3, "bottom", 0.5).tolist()
    [[0.0, 0.5, 0.5], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    """
    # the paper's weights (contact_weights: sympy-free) placed as redistribution_matrix
    # places them, in floats: a numeric scene does not load sympy (tested equal)
    R = np.eye(n)
    for c, ws in contact_weights(n, contact, gamma_s).items():
        R[c, c] = 0.0
        for j, w in ws.items():
            R[c, j] = float(w)
    return R
