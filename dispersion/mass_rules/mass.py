"""Mass matrix variants: consistent, row-sum lumped, and singular (paper eqs 1-4).

The singular mass moves each contact shape function onto its neighbours,

.. math::

    N_{j,m} = N_j + \\sum_{c} w_{cj} N_c \\quad (j \\notin \\mathcal{C}), \\qquad
    N_{c,m} = 0 \\quad (c \\in \\mathcal{C}),

i.e. :math:`\\mathbf N_m = \\mathbf N \\mathbf R` with the redistribution matrix
:math:`\\mathbf R` (row c holds the weights :math:`w_{cj}`, non-contact rows are unit rows).
Then :math:`\\mathbf M_{m} = \\mathbf R^T \\mathbf M \\mathbf R` (eq 1, left) and its
row-sum lumped form :math:`\\int \\rho \\mathbf N_m` (eq 1, right). Weights summing to one
keep the translational mass; weights in [0, 1] keep the lumped form non-negative.

The paper's quadratic element (eqs 2-4) with contact at node 3 sends :math:`\\gamma_s` of
:math:`N_3` to the far node 1 and :math:`1-\\gamma_s` to the neighbour node 2:

>>> import sympy
>>> R = redistribution_matrix(3, contact_weights(3, "top", sympy.Rational(1, 2)))
>>> R.tolist()
[[1, 0, 0], [0, 1, 0], [1/2, 1/2, 0]]

Works on sympy matrices (exact) and on numpy / scipy.sparse arrays alike; sympy and scipy
are imported only where such a matrix is made or met, so a numeric scene runs on numpy alone.

References
----------
A. Tkachuk, M. Matzen, R. Kolman, M. Bischoff, "Singular mass matrices for isogeometric
finite element analysis of dynamic contact", eqs (1)-(4).
"""
from __future__ import annotations

import warnings
from collections.abc import Mapping

from typing import TYPE_CHECKING

from dispersion import defaults
from dispersion.errors import (IndefiniteMassWarning, InputError, as_real, check_choice,
                     check_positive_int, check_real_in_range)
from dispersion.splines.matrix_kind import is_exact, is_sparse

if TYPE_CHECKING:
    import sympy

__all__ = [
    "CONTACT_SETS",
    "contact_weights",
    "redistribution_matrix",
    "redistributed_mass",
    "row_sum_lump",
]

CONTACT_SETS = defaults.CONTACT_SETS


def contact_weights(n: int, contact: str = "top", gamma_s=0) -> dict[int, dict[int, object]]:
    """Weights of the paper's redistribution across ``n`` control points through the thickness.

    A contact point sends ``1 - gamma_s`` to its nearest neighbour inward and ``gamma_s``
    to the next one (paper eqs 2-3: for n = 3 the next one is the far surface).
    ``contact`` is ``"top"`` (index n-1), ``"bottom"`` (index 0) or ``"both"``.

    >>> contact_weights(3, "top", 0)
    {2: {1: 1}}
    """
    check_choice("contact", contact, CONTACT_SETS)
    gamma_s = check_real_in_range("gamma_s", gamma_s, 0, 1)
    check_positive_int("n (control points through the thickness)", n, minimum=3)
    top = {n - 1: {n - 2: 1 - gamma_s, n - 3: gamma_s}}
    bottom = {0: {1: 1 - gamma_s, 2: gamma_s}}
    weights = {"top": top, "bottom": bottom, "both": {**bottom, **top}}[contact]
    return {c: {j: w for j, w in ws.items() if w != 0} for c, ws in weights.items()}


def redistribution_matrix(
    n: int,
    weights: Mapping[int, Mapping[int, object]],
    *,
    allow_negative: bool = False,
    tol: float = 1e-12,
) -> sympy.Matrix:
    """Matrix ``R`` with ``N_m = N R`` for contact points ``weights.keys()``.

    Parameters
    ----------
    n : int
        Number of basis functions.
    weights : mapping ``{contact index c: {neighbour index j: w_cj}}``
        Each contact function's weights must target non-contact functions and sum to one.
    allow_negative : bool
        Weights outside [0, 1] raise :class:`InputError` unless this is set; then they give
        an :class:`IndefiniteMassWarning` (the lumped singular mass loses definiteness).
    """
    import numpy as np
    import sympy

    n = check_positive_int("n (number of basis functions)", n, minimum=2)
    check_real_in_range("tol", tol, 0, 1)
    if not isinstance(weights, Mapping) or not all(isinstance(ws, Mapping)
                                                   for ws in weights.values()):
        raise InputError("weights must be a mapping {contact index: {neighbour index: weight}}")
    indices = list(weights) + [j for ws in weights.values() for j in ws]
    if any(isinstance(i, bool) or not isinstance(i, (int, np.integer)) for i in indices):
        raise InputError(f"weight indices must be integers in [0, {n - 1}], got {indices}")
    for c, ws in weights.items():
        for j, w in ws.items():
            as_real(f"weight w[{c}][{j}]", w, "a finite real number")
    contact = set(weights)
    if not contact:
        raise InputError("the contact set must hold at least one control point")
    if any(not (0 <= c < n) for c in contact):
        raise InputError(f"contact indices must lie in [0, {n - 1}], got {sorted(contact)}")
    if len(contact) == n:
        raise InputError("at least one control point must stay out of the contact set")
    R = sympy.eye(n)
    for c, ws in weights.items():
        if not ws:
            raise InputError(f"contact point {c} has no redistribution weights")
        bad = [j for j in ws if j in contact or not (0 <= j < n)]
        if bad:
            raise InputError(
                f"weights of contact point {c} must target non-contact indices in [0, {n - 1}], "
                f"got {bad}")
        total = sum(ws.values())
        if abs(float(total) - 1) > tol:
            raise InputError(
                f"weights of contact point {c} must sum to 1 (translational mass), got {total}")
        outside = [w for w in ws.values() if not (0 <= w <= 1)]
        if outside:
            msg = f"weights of contact point {c} must lie in [0, 1], got {outside}"
            if not allow_negative:
                raise InputError(msg)
            warnings.warn(msg + ": the lumped singular mass may be indefinite", IndefiniteMassWarning,
                          stacklevel=2)
        R[c, c] = 0
        for j, w in ws.items():
            R[c, j] = sympy.nsimplify(w) if isinstance(w, float) else w
    return R


def row_sum_lump(M):
    """Diagonal matrix of row sums of ``M`` (sympy, numpy or scipy.sparse in, same kind out)."""
    import numpy as np
    if is_exact(M):
        import sympy

        return sympy.diag(*[sum(M.row(i)) for i in range(M.rows)])
    if is_sparse(M):
        import scipy.sparse as sp

        return sp.diags(np.asarray(M.sum(axis=1)).ravel()).tocsr()
    return np.diag(np.asarray(M).sum(axis=1))


def redistributed_mass(M, R, lumped: bool = False):
    """:math:`R^T M R` (eq 1 left), or its row sums with ``lumped=True`` (eq 1 right)."""
    import numpy as np
    if is_exact(M):
        import sympy

        R = sympy.Matrix(R)
        Mm = R.T * M * R
    else:
        if not is_sparse(R):
            R = np.asarray(R, dtype=float)
        Mm = R.T @ M @ R
    return row_sum_lump(Mm) if lumped else Mm
