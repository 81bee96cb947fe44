"""The contact step's linear complementarity problem on the constrained DOFs.

For a linear problem the step matrix is factorized once; the contact multipliers of a step
solve :math:`\\boldsymbol\\mu \\ge 0`, :math:`\\mathbf S \\boldsymbol\\mu + \\mathbf q \\ge 0`,
:math:`\\boldsymbol\\mu \\cdot (\\mathbf S \\boldsymbol\\mu + \\mathbf q) = 0` with the Schur
complement :math:`\\mathbf S` of the constraints.

>>> import numpy as np
>>> solve_lcp(np.array([[2.0]]), np.array([-1.0]), 10).tolist()   # mu = 1/2, gap closed
[0.5]

References
----------
M. Hintermueller, K. Ito, K. Kunisch, "The primal-dual active set strategy as a semismooth
Newton method", SIAM J. Optim. 13 (2003).
"""
from __future__ import annotations

import numpy as np

from dispersion.errors import ConvergenceError

__all__ = ["solve_lcp"]


def solve_lcp(S: np.ndarray, q: np.ndarray, max_iter: int) -> np.ndarray:
    """``mu >= 0`` with ``S mu + q >= 0`` and ``mu . (S mu + q) = 0`` (primal-dual active set)."""
    if len(q) == 1:  # one contact point: the complementarity solution in closed form
        return np.array([max(0.0, -q[0] / S[0, 0])])
    act = q < 0
    mu = np.zeros(len(q))
    for _ in range(max_iter + len(q)):
        mu[:] = 0
        if act.any():
            mu[act] = np.linalg.solve(S[np.ix_(act, act)], -q[act])
        w = S @ mu + q
        new = (mu - w) > 0
        if np.array_equal(new, act):
            return mu
        act = new
    raise ConvergenceError(f"contact active set did not settle in {max_iter + len(q)} sweeps")
