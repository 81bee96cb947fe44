"""The kinds of matrix the mass code meets: exact (sympy), sparse (scipy) or dense (numpy).

The tests never import sympy or scipy: a matrix of such a kind means its library is loaded
already, so a float scene that never makes one runs on numpy alone.

>>> import numpy as np
>>> is_exact(np.eye(2)), is_sparse(np.eye(2)), total(np.eye(2))
(False, False, 2.0)
"""
from __future__ import annotations

import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # numpy is imported where a float matrix is handled
    import numpy as np

__all__ = ["is_exact", "is_sparse", "total", "dense"]


def is_exact(M) -> bool:
    """True for a sympy matrix; never imports sympy (such a matrix means it is loaded)."""
    sympy = sys.modules.get("sympy")
    return sympy is not None and isinstance(M, sympy.MatrixBase)


def is_sparse(M) -> bool:
    """True for a scipy.sparse matrix; never imports scipy (such a matrix means it is loaded)."""
    sp = sys.modules.get("scipy.sparse")
    return sp is not None and sp.issparse(M)


def total(M):
    """Sum of all entries (exact for a sympy matrix, a float otherwise)."""
    import numpy as np
    if is_exact(M):
        return sum(M)
    return float(np.asarray(M.sum()))


def dense(M) -> np.ndarray:
    """``M`` as a dense float numpy array."""
    import numpy as np
    if is_exact(M):
        return np.array(M.tolist(), dtype=float)
    return M.toarray() if is_sparse(M) else np.asarray(M, dtype=float)
