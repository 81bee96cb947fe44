"""What a mass matrix is, measured, against what its rule states.

:class:`MassProperties` are stated by a rule (:class:`dispersion.mass_rules.mass_rule.MassRule`)
or measured on a matrix; :func:`check_mass` measures them and gives the verdict: a matrix that
contradicts its rule's statement, is not symmetric, or has massless directions that are not
zero rows (the explicit scheme condenses zero rows only) is refused with the reason; an
indefinite matrix or lost translational mass is warned about. ``rule`` is anything with a
``name`` and stated properties ``states``.

>>> import numpy as np
>>> from types import SimpleNamespace
>>> rule = SimpleNamespace(name="diag", states=MassProperties(diagonal=True))
>>> check_mass(rule, np.diag([1.0, 0.0]), np.ones((2, 2)) / 2).refused
('it has zero rows [1] but does not state zero_rows',)
"""
from __future__ import annotations

from dataclasses import dataclass, fields

from dispersion.errors import InputError
from dispersion.splines.matrix_kind import dense, is_exact, total

__all__ = ["MassProperties", "MassCheck", "check_mass", "DENSE_CHECK_MAX"]


@dataclass(frozen=True)
class MassProperties:
    """Properties of a mass matrix, stated by a rule or measured on a space.

    ``zero_rows``: the matrix may have (stated) or has (measured) identically zero rows, the
    massless DOFs the explicit scheme condenses.
    """

    symmetric: bool = True
    psd: bool = True
    translational: bool = True
    diagonal: bool = False
    zero_rows: bool = False

    def as_dict(self) -> dict:
        return {f.name: getattr(self, f.name) for f in fields(self)}


@dataclass(frozen=True)
class MassCheck:
    """Properties measured on a space, and the reasons a rule is refused or warned about."""

    measured: MassProperties
    refused: tuple[str, ...]
    warned: tuple[str, ...]


def check_mass(rule, Mv, M, tol: float = 1e-10) -> MassCheck:
    """Measure the properties of ``Mv`` (built by ``rule`` from the consistent ``M``).

    Refused: not symmetric; stated diagonal but is not; zero rows it did not state; a
    massless direction that is no zero row. Warned: indefinite; translational mass changed
    (the warning says if the rule stated otherwise). ``tol`` is relative to the largest entry (float matrices; exact ones compare
    exactly, except the eigenvalues).
    """
    import numpy as np
    exact = is_exact(Mv)
    if exact:
        import sympy
    if not exact and Mv.shape[0] > DENSE_CHECK_MAX:
        return _check_large(rule, Mv, M, tol)
    A = dense(Mv)
    n = A.shape[0]
    if A.shape != (n, n) or A.shape[0] != M.shape[0]:
        raise InputError(f"mass rule {rule.name!r} returned shape {A.shape}, expected "
                         f"{tuple(M.shape)}")
    if not np.all(np.isfinite(A)):
        raise InputError(f"mass rule {rule.name!r} returned non-finite entries")
    scale = max(float(np.abs(A).max(initial=0.0)), np.finfo(float).tiny)
    if exact:
        symmetric = Mv.is_symmetric()
        diagonal = Mv.is_diagonal()
        zero = [i for i in range(n) if all(v == 0 for v in Mv.row(i))]
        translational = sympy.expand(sum(Mv) - sum(sympy.Matrix(M))) == 0 \
            if is_exact(M) else abs(float(sum(Mv)) - total(M)) <= tol * scale * n
    else:
        symmetric = bool(np.allclose(A, A.T, rtol=0, atol=tol * scale))
        diagonal = bool(np.all(np.abs(A - np.diag(np.diag(A))) <= tol * scale))
        zero = [i for i in range(n) if np.all(np.abs(A[i]) <= tol * scale)]
        translational = abs(A.sum() - total(M)) <= tol * scale * n
    keep = np.flatnonzero(~np.isin(np.arange(n), zero)) if zero else np.arange(n)
    Ar = A[np.ix_(keep, keep)]
    ev = np.linalg.eigvalsh((Ar + Ar.T) / 2) if keep.size else np.zeros(0)
    psd = bool(ev.size == 0 or ev.min() >= -tol * scale * n)
    if exact and keep.size:
        # rank decided exactly (fraction-free over QQ): high-degree nodal masses are
        # nonsingular but far too ill-conditioned for a float test
        from sympy.polys.matrices import DomainMatrix

        rest = Mv.extract(list(keep), list(keep))
        try:
            nonsingular_rest = DomainMatrix.from_Matrix(rest).to_field().rank() == keep.size
        except (ValueError, TypeError, NotImplementedError, sympy.polys.polyerrors.PolynomialError):
            nonsingular_rest = bool(np.abs(ev).min() > tol * scale * n)
    else:
        nonsingular_rest = bool(ev.size == 0 or np.abs(ev).min() > tol * scale * n)
    measured = MassProperties(bool(symmetric), psd, bool(translational), bool(diagonal),
                              bool(zero))
    smallest = f"smallest eigenvalue {ev.min():.3g}" if ev.size else ""
    return _verdict(rule, measured, zero, nonsingular_rest, smallest)


#: Largest float matrix checked with dense eigenvalues; above, a sparse symmetric
#: factorisation gives the inertia (Sylvester). Rule: the dense check stays near a second
#: (numpy eigvalsh of 2000 x 2000, O(n^3)) and its memory near 32 MB.
DENSE_CHECK_MAX = 2000


def _check_large(rule, Mv, M, tol: float) -> MassCheck:
    """:func:`check_mass` of a large float matrix without forming it densely."""
    import numpy as np
    import scipy.sparse as sp
    from scipy.sparse.linalg import splu

    A = sp.csr_matrix(Mv, dtype=float)
    n = A.shape[0]
    if A.shape != (n, n) or n != M.shape[0]:
        raise InputError(f"mass rule {rule.name!r} returned shape {A.shape}, expected "
                         f"{tuple(M.shape)}")
    if not np.all(np.isfinite(A.data)):
        raise InputError(f"mass rule {rule.name!r} returned non-finite entries")
    scale = max(float(np.abs(A.data).max(initial=0.0)), np.finfo(float).tiny)
    symmetric = float(np.abs((A - A.T).data).max(initial=0.0)) <= tol * scale
    off = A - sp.diags(A.diagonal())
    diagonal = float(np.abs(off.data).max(initial=0.0)) <= tol * scale
    rowabs = np.asarray(abs(A).sum(axis=1)).ravel()
    zero = [int(i) for i in np.flatnonzero(rowabs <= tol * scale)]
    translational = abs(float(A.sum()) - total(M)) <= tol * scale * n
    keep = np.setdiff1d(np.arange(n), zero)
    S = ((A + A.T) / 2).tocsc()[keep][:, keep]
    if diagonal:
        pivots = S.diagonal()
    else:  # LDL^T by symmetric-mode LU without pivoting: the pivots carry the inertia
        try:
            pivots = splu(S, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                          options={"SymmetricMode": True}).U.diagonal()
        except RuntimeError:  # exactly singular
            pivots = np.zeros(1)
    psd = bool(pivots.size == 0 or pivots.min() >= -tol * scale)
    nonsingular_rest = bool(pivots.size == 0 or np.abs(pivots).min() > tol * scale)
    measured = MassProperties(bool(symmetric), psd, bool(translational), bool(diagonal),
                              bool(zero))
    smallest = f"smallest pivot {pivots.min():.3g}" if pivots.size else ""
    return _verdict(rule, measured, zero, nonsingular_rest, smallest)


def _verdict(rule, measured: MassProperties, zero, nonsingular_rest: bool,
             smallest: str) -> MassCheck:
    refused, warned = [], []
    if not measured.symmetric:
        refused.append("it is not symmetric")
    if not nonsingular_rest:
        refused.append("it has massless directions that are not zero rows (the explicit "
                       "scheme condenses zero rows only)")
    if zero and not rule.states.zero_rows:
        refused.append(f"it has zero rows {zero} but does not state zero_rows")
    if rule.states.diagonal and not measured.diagonal:
        refused.append("it states diagonal but is not")
    # indefinite or mass-changing matrices are legitimate objects of study (negative weights
    # on request, mass scaling): warned, with the stated promise named if it is broken
    if not measured.psd:
        broken = " although it states psd" if rule.states.psd else ""
        warned.append(f"it is indefinite ({smallest}){broken}")
    if not measured.translational:
        broken = " although it states translational" if rule.states.translational else ""
        warned.append(f"it changes the translational mass{broken}")
    return MassCheck(measured, tuple(refused), tuple(warned))
