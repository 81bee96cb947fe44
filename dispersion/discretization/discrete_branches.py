"""Discrete dispersion branches of the plate patch: all finite roots of det(K - Omega^2 M) = 0.

For each :math:`\\kappa` of a grid the pencil :math:`(K, M)` of
:func:`dispersion.symbolic.plate.numeric_pencil` is solved in batches
(:mod:`dispersion.discretization.pencil_frequencies`; the error against the exact branches and its
order are in :mod:`dispersion.discretization.discrete_error`). Massless DOFs
(singular masses, :attr:`PlatePatch.massless`) carry infinite eigenvalues and are never formed:

.. math::

    \\hat K = K_{rr} - K_{rm} K_{mm}^{-1} K_{mr}, \\qquad
    \\det(\\hat K - \\Omega^2 M_{rr}) = 0.

Accuracy at every kappa, at full speed (issue 23). Where a block of the pencil is small
(:data:`dispersion.discretization.pencil_polynomial.MAX_BLOCK`), its characteristic polynomial
:math:`P(u, \\mu)` is known exactly (:mod:`dispersion.discretization.pencil_polynomial`: the rigid-body
cancellation at small kappa done once, in rational arithmetic). Its roots are Newton-polished
from guesses interpolated between anchors (every :data:`ANCHOR_STRIDE`-th kappa solved by the
float eigen-solver) and *certified* by an inclusion radius from a running error bound:
:math:`\\Omega` to :data:`CERTIFIED_RTOL` relative, A0 (:math:`\\Omega^2 \\sim \\kappa^4`) and S0
(:math:`\\kappa^2`) included. Where the polynomial cannot certify a root, the float eigenvalue
is used if its error bound :math:`m\\epsilon \\max(\\lambda_{max}, \\|K\\| \\|M^{-1}\\|)/\\lambda`
(the conditioning of M counts, :func:`~dispersion.discretization.pencil_frequencies.eigenvalue_error`)
is small enough,
else that kappa is solved in ball arithmetic
(:func:`~dispersion.discretization.extended_pencil.extended_frequencies`), and where that
fails too the kappa is listed in ``DiscreteBranches.failures`` with the reason: nothing
raises from an eigen-solver. Below :data:`KAPPA_TINY` every branch follows its leading power
law exactly to the precision of floats; a frequency that underflows is listed, not guessed.

Where the mass keeps the mirror symmetry y -> -y (:func:`dispersion.symbolic.plate.mirror_bases`),
the pencil splits into a symmetric and an antisymmetric block and the branches are labelled
``S0, S1, ...`` and ``A0, A1, ...`` in increasing :math:`\\Omega` (within a block they cannot
cross). Otherwise the symmetry is ``"mixed"``: a branch is labelled by the dominant mirror
parity of its mode shape, and the label says so. The Bloch model is periodic in
:math:`\\kappa` with period :math:`2\\pi/r`; beyond the zone edge :math:`\\pi/r` its branches are
the folded ones.

>>> from dispersion.symbolic.plate import plate_patch
>>> br = discrete_branches(plate_patch(), 0.3, [0.5, 1.0])
>>> sorted(br.omega), br.symmetry["S0"]
(['A0', 'A1', 'A2', 'S0', 'S1', 'S2'], 'S')

References
----------
A. Tkachuk et al., section 2, eq (16) and Figure 2. G. H. Golub, C. F. Van Loan, *Matrix
computations*, 4th ed., section 8.7 (symmetric-definite pencils).
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, replace

import numpy as np
import sympy

from dispersion.branch_views import BranchViews
from dispersion.errors import InputError, check_positive_int, check_wavenumbers
from dispersion.symbolic.plate import (
    PlatePatch,
    mirror_bases,
    numeric_pencil,
    numeric_terms,
    with_nu,
    x_functions,
)
from dispersion.discretization.extended_pencil import refine_inaccurate
from dispersion.discretization.pencil_frequencies import congruence, pencil_frequencies

__all__ = [
    "DiscreteBranches",
    "discrete_branches",
    "fundamental_branches",
    "pencil_derivative",
]


@dataclass(repr=False)  # BranchViews: a short repr, no whole arrays
class DiscreteBranches(BranchViews):
    """Discrete branches on a kappa grid.

    ``omega[label]`` has one entry per kappa (NaN where that branch does not exist there);
    ``symmetry[label]`` is ``"S"``, ``"A"`` or ``"mixed"``; ``zone_edge`` is :math:`\\pi/r`
    for the Bloch model (None for x-exact).
    """

    kappa: np.ndarray
    omega: dict[str, np.ndarray]
    symmetry: dict[str, str]
    zone_edge: float | None = None
    #: ``label -> dOmega/dkappa`` (group velocity over c_T) when asked for, else None.
    group: dict[str, np.ndarray] | None = None
    #: ``(quantity, kappa, reason)`` for every kappa where a frequency (``"omega"``, then NaN
    #: in ``omega``) or a group velocity (``"group"``, value kept) is not certified to
    #: :data:`RTOL` (frequencies) or :data:`GROUP_RTOL` (slopes). Never silently dropped.
    failures: list[tuple[str, float, str]] = field(default_factory=list)
    #: Kappa points per route (:data:`ROUTES`), each counted once by the costliest route
    #: any of its blocks took: the certified polynomial, the float eigen-solver's own bound,
    #: the extended-precision solve, the power law below :data:`KAPPA_TINY`.
    routes: dict[str, int] = field(default_factory=dict)

    def failure_lines(self) -> tuple[str, ...]:
        """Every failure in words, one line each (for JSON ``failures`` and CSV ``# failure:``).

        >>> DiscreteBranches(np.zeros(1), {}, {}, failures=[("group", 0.5, "why")]).failure_lines()
        ('group velocity at kappa=0.5: why',)
        """
        what = {"omega": "frequency", "group": "group velocity"}
        return tuple(f"{what.get(q, q)} at kappa={k:.6g}: {why}" for q, k, why in self.failures)


#: The routes of :attr:`DiscreteBranches.routes`, cheapest first.
ROUTES = ("polynomial", "float eigen-solver", "extended precision", "power law")


RTOL = 1e-11


def pencil_derivative(patch: PlatePatch, nu, kappa) -> tuple[np.ndarray, np.ndarray]:
    """:math:`dK/d\\kappa` and :math:`dM/d\\kappa` as float stacks, by the complex step.

    The x-functions of :func:`dispersion.symbolic.plate.x_functions` (polynomials or trigonometric sums
    in kappa) are evaluated at :math:`\\kappa + i\\,10^{-30}`; the imaginary part over the
    step is the derivative to rounding, with no cancellation (Squire and Trapp 1998).

    >>> from dispersion.symbolic.plate import plate_patch
    >>> dK, dM = pencil_derivative(plate_patch(model="x-exact"), 0.3, [0.5])
    >>> bool(np.allclose(dK, dK.transpose(0, 2, 1))), float(np.abs(dM).max())  # x-exact: M const
    (True, 0.0)
    """
    patch = with_nu(patch, nu)
    h = 1e-30
    kappa = np.atleast_1d(np.asarray(kappa, dtype=float)) + 1j * h
    mat, xf = patch.law.float_moduli(), x_functions(patch, kappa)
    n2 = 2 * patch.n
    terms, M0 = numeric_terms(patch)
    dK = np.zeros((kappa.size, n2, n2))
    for m, f, B in terms:
        dK += (mat[m] * np.imag(np.asarray(xf[f], dtype=complex)) / h)[:, None, None] * B
    dmx = np.imag(np.broadcast_to(np.asarray(xf["mx"], dtype=complex), kappa.shape)) / h
    dM = dmx[:, None, None] * M0
    return dK, dM


def _slopes(W, X, dK, dM, M):
    """Hellmann-Feynman :math:`d\\Omega/d\\kappa` of every mode (columns of X) of a stack."""
    num = np.einsum("kim,kij,kjm->km", X, dK, X) - W**2 * np.einsum("kim,kij,kjm->km", X, dM, X)
    den = 2 * W * np.einsum("kim,kij,kjm->km", X, M, X)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(W > 0, num / den, np.nan)


def discrete_branches(patch: PlatePatch, nu, kappa, chunk: int = 20000,
                      progress=None, group: bool = False) -> DiscreteBranches:
    """All finite discrete branches of ``patch`` on the grid ``kappa`` (see module docstring).

    Parameters
    ----------
    patch : PlatePatch
        From :func:`dispersion.symbolic.plate.plate_patch` (numeric aspect ratio for the Bloch
        model), with its material: a numeric :attr:`~PlatePatch.law` (e.g.
        ``plate_patch(nu=0.3)``).
    kappa : array_like
        :math:`\\kappa = kh \\ge 0`.
    chunk : int
        Kappa points per batched solve (bounds the memory).
    progress : callable, optional
        Called with the number of kappa points finished after each chunk.
    group : bool
        Also the group velocity :math:`d\\Omega/d\\kappa` of every branch (eigenvector
        formula, :mod:`dispersion.continuum.velocities`), in ``DiscreteBranches.group``.

    Never raises from an eigen-solver: what cannot be certified is listed in
    ``DiscreteBranches.failures``.
    """
    patch = with_nu(patch, nu)
    if patch.model == "bloch" and isinstance(patch.r, sympy.Symbol):
        raise InputError("aspect ratio r must be a number for discrete branches, got the symbol r")
    patch.law.check_numeric("discrete branches")
    kappa = check_wavenumbers(kappa)
    chunk = check_positive_int("chunk", chunk)
    workers = min(THREADS, os.cpu_count() or 1)
    if workers > 1 and kappa.size >= 2 * MIN_SHARE:
        # equal chunks, a multiple of the workers in number: no core idles at the end
        count = -(-kappa.size // chunk)
        count = -(-count // workers) * workers
        chunk = -(-kappa.size // count)
    zone = math.pi / float(patch.r) if patch.model == "bloch" else None
    plan = _plan(patch, None)
    failures = []
    starts = range(0, kappa.size, chunk)

    def work(lo):
        return _branches_block(patch, kappa[lo:lo + chunk], group, plan, failures)

    workers = min(workers, len(starts))
    if workers > 1:  # numpy releases the GIL in its loops: chunks run on both cores
        from concurrent.futures import ThreadPoolExecutor

        with ThreadPoolExecutor(workers) as pool:
            parts = []
            for lo, part in zip(starts, pool.map(work, starts)):
                parts.append(part)
                if progress is not None:
                    progress(min(chunk, kappa.size - lo))
    else:
        parts = []
        for lo in starts:
            parts.append(work(lo))
            if progress is not None:
                progress(min(chunk, kappa.size - lo))
    failures.sort(key=lambda f: (f[1], f[0], f[2]))
    symmetry = {}
    for part in parts:
        symmetry.update(part[1])
    route = np.concatenate([part[3] for part in parts])
    routes = {name: int(np.count_nonzero(route == i)) for i, name in enumerate(ROUTES)}
    sizes = [min(chunk, kappa.size - lo) for lo in range(0, kappa.size, chunk)]

    def join(i):
        return {lab: np.concatenate([part[i].get(lab, np.full(m, np.nan))
                                     for part, m in zip(parts, sizes)]) for lab in symmetry}

    return DiscreteBranches(kappa, join(0), symmetry, zone, join(2) if group else None,
                            failures, routes)


#: Below this kappa every branch is its leading power law: :math:`\\Omega = a\\kappa^e (1 +
#: O(\\kappa^2))`, e in {0, 1, 2}, so :math:`\\Omega(\\kappa) = \\Omega(\\kappa_0)
#: (\\kappa/\\kappa_0)^e` with :math:`\\kappa_0` = KAPPA_TINY is exact to a relative
#: O(1e-40) (the x-functions are analytic and even or odd in kappa). It keeps u = kappa^2
#: and its powers clear of underflow.
KAPPA_TINY = 1e-20
#: Relative accuracy of Omega certified on the polynomial path (the inclusion radius is a
#: worst-case bound, twice the standard rounding constants; the actual error is ~1e-15).
CERTIFIED_RTOL = 1e-10
#: Relative accuracy certified for the group velocities (:func:`pencil_polynomial.slopes`).
GROUP_RTOL = 1e-12
#: Worker threads over the kappa chunks (the machine this was tuned on has two cores).
THREADS = 2
#: Fewest kappa per thread: below it the threads' start-up costs more than they save.
MIN_SHARE = 2048
#: Anchors of the root guesses: every ANCHOR_STRIDE-th kappa (sorted) is solved by the float
#: eigen-solver; guesses between anchors are interpolated, then polished and certified
#: (a guess that falls to the wrong root is caught by the disjoint discs and redone). 64:
#: the anchors then cost under 2 % (measured, 100,000 kappa, p = 2 and 3: 5-10 % faster
#: than 16, with the same fallback counts).
ANCHOR_STRIDE = 64


@dataclass(frozen=True)
class _Block:
    kind: str | None            # "S", "A" or None (the whole pencil, mixed labels)
    E: np.ndarray | None        # orthonormal float basis (None: all DOFs)
    massless: tuple[int, ...]   # massless DOFs within the block
    poly: object                # PencilPolynomial or None (eigen-solver path)


def _plan(patch: PlatePatch, nu) -> list[_Block]:
    """The blocks of the pencil and, where small enough, their exact characteristic polynomial."""
    patch = with_nu(patch, nu)
    from dispersion.discretization import pencil_polynomial as pp

    massless = set(patch.massless)
    bases = mirror_bases(patch)
    blocks = []
    if bases is None:
        groups = [(None, None, tuple(sorted(massless)), None)]
    else:
        exact = mirror_bases(patch.n, exact=True)
        groups = []
        for kind in ("S", "A"):
            E = bases[kind]
            support = [set(np.flatnonzero(np.abs(E[:, j]) > 0)) for j in range(E.shape[1])]
            if any(s & massless and not s <= massless for s in support):
                raise InputError("mirror basis mixes massless and massive DOFs")
            ml = tuple(j for j, s in enumerate(support) if s <= massless)
            groups.append((kind, E, ml, exact[kind]))
    for kind, E, ml, Eq in groups:
        poly = None
        try:
            poly = pp.pencil_polynomial(patch, None, Eq, parity=kind is None)
            if poly.degree != (2 * patch.n if E is None else E.shape[1]) - len(ml):
                poly = None
        except InputError:
            poly = None  # too large, or a singular interpolation node: eigen-solver path
        blocks.append(_Block(kind, E, ml, poly))
    return blocks


def _eigen_block(patch, kappa, block: _Block, vectors: bool):
    """Float eigen-solve of one block at ``kappa``: (W, X or None, dK/dM-ready pencil, the
    relative error bound of each W^2)."""
    K, M = numeric_pencil(patch, None, kappa)
    if block.E is not None:
        K, M = congruence(block.E.T, K), congruence(block.E.T, M)
    if vectors:
        W, X, err = pencil_frequencies(K, M, block.massless, vectors=True, bounds=True)
        return W, X, M, err
    W, err = pencil_frequencies(K, M, block.massless, bounds=True)
    return W, None, M, err


def _parity_from_vectors(patch, X):
    S = mirror_bases(replace(patch, My=patch.Y["00"]))["S"]
    return np.sum((S.T @ X) ** 2, axis=1) / np.sum(X**2, axis=1)


def _solve_block(patch, kappa, block: _Block, group: bool, failures: list):
    """``(W, G, share, route)`` of one block at kappa (no tiny kappa here): W ascending per
    row, route the index in :data:`ROUTES` of each kappa."""
    from dispersion.discretization import pencil_polynomial as pp
    from dispersion.discretization.certified_roots import certified_roots
    from dispersion.discretization.certified_slopes import ball_slopes

    n = kappa.size
    mixed = block.kind is None
    W = G = share = None
    todo = np.arange(n)
    route = np.zeros(n, dtype=np.int8)
    poly = block.poly
    if poly is not None:
        r = None if patch.model != "bloch" else float(patch.r)
        u, v, dudk = pp.u_of_kappa(patch.model, r, kappa)
        # the roots are functions of u (S0 ~ u, A0 ~ u^2, cut-offs ~ const + u): guesses are
        # interpolated in u between anchors solved by the float eigen-solver
        order = np.argsort(u, kind="stable")
        anchors = order if n <= 4 * ANCHOR_STRIDE else \
            np.concatenate([order[::ANCHOR_STRIDE], order[-1:]])
        Wa, _, _, Ea = _eigen_block(patch, kappa[anchors], block, False)
        mx = pp.mass_factor(poly, u, v)
        mua = Wa**2 * mx[anchors]
        ua = u[anchors]
        guess = np.column_stack([np.interp(u, ua, mua[:, j]) for j in range(mua.shape[1])])
        mu, rad = certified_roots(poly, u, v, guess, 2 * CERTIFIED_RTOL, kappa=kappa)
        with np.errstate(all="ignore"):
            ok = np.all((mu > 0) & (rad <= 2 * CERTIFIED_RTOL * mu), axis=1)
        redo = np.flatnonzero(~ok)
        if redo.size:
            # guesses that fell to the wrong root (close roots) or radii too wide: the float
            # eigen-solver at those kappa; a root whose radius stays too wide may still be
            # certified by the eigen-solver's own bound (large roots, where float
            # eigenvalues are accurate)
            if anchors.size == n:  # every kappa is an anchor: its eigenvalues are at hand
                Wr, Er = np.empty_like(Wa), np.empty_like(Ea)
                Wr[anchors], Er[anchors] = Wa, Ea
                Wr, Er = Wr[redo], Er[redo]
            else:
                Wr, _, _, Er = _eigen_block(patch, kappa[redo], block, False)
            # where every disc is finite (hence disjoint: one root each, all roots found) the
            # roots are the right ones, only some too loosely enclosed: no second polish
            m2, r2 = mu[redo], rad[redo]
            lost = np.flatnonzero(np.any(~np.isfinite(r2), axis=1))
            if lost.size:
                at = redo[lost]
                m2[lost], r2[lost] = certified_roots(poly, u[at], None if v is None else v[at],
                                                        Wr[lost]**2 * mx[at], 2 * CERTIFIED_RTOL,
                                                        kappa=kappa[at])
            with np.errstate(all="ignore"):
                by_poly = (m2 > 0) & (r2 <= 2 * CERTIFIED_RTOL * m2)
                by_eig = Er <= 2 * CERTIFIED_RTOL
            m2 = np.where(by_poly, m2, Wr**2 * mx[redo])
            with np.errstate(all="ignore"):   # the bound used (inf where there is none)
                rad[redo] = np.where(by_poly, r2, np.where(np.isfinite(Er), Er * m2, np.inf))
            mu[redo] = m2
            ok[redo] = np.all(by_poly | by_eig, axis=1)
            route[redo[~np.all(by_poly, axis=1)]] = 1
        with np.errstate(all="ignore"):
            W = np.sqrt(mu / mx)
        if group:
            G, Gerr = pp.slopes(poly, u, v, dudk, mu, rad)
            loose = np.flatnonzero(ok & np.any(~(Gerr <= GROUP_RTOL * np.abs(G)), axis=1))
            if loose.size:   # the float bound too wide: the same formula in balls
                Gb, rel = ball_slopes(poly, kappa[loose], mu[loose])
                sure = rel <= GROUP_RTOL
                G[loose] = np.where(sure, Gb, G[loose])
                _group_failures(failures, kappa[loose], rel, Gb, block.kind)
        if mixed:
            share = pp.parity_share(poly, u, v, mu)
        todo = np.flatnonzero(~ok)
    if todo.size:
        W, G, share = _eigen_fallback(patch, kappa, block, group, todo, W, G, share,
                                      failures, route)
        if group and poly is not None:   # the slopes of those roots, certified in balls
            mx_t = pp.mass_factor(poly, *pp.u_of_kappa(patch.model, r, kappa[todo])[:2])
            Gb, rel = ball_slopes(poly, kappa[todo], W[todo] ** 2 * mx_t)
            G[todo] = np.where(rel <= GROUP_RTOL, Gb, G[todo])
            _group_failures(failures, kappa[todo], rel, Gb, block.kind)
        elif group:
            fresh = todo[route[todo] == ROUTES.index("float eigen-solver")]
            for kk in kappa[fresh]:
                failures.append(("group", float(kk), "group velocity from the float "
                                 "eigen-solver (eigenvector formula): not certified to "
                                 f"{GROUP_RTOL:.0e}"))
    return W, G, share, route


def _group_failures(failures, kappa, rel, G, kind):
    """One ``("group", kappa, reason)`` per kappa where a ball slope is wider than GROUP_RTOL."""
    for i in np.flatnonzero(np.any(~(rel <= GROUP_RTOL), axis=1)):
        j = int(np.argmax(np.where(np.isfinite(rel[i]), rel[i], np.inf)))
        failures.append(("group", float(kappa[i]),
                         f"group velocity of root {j} ({kind or 'mixed'} block) not certified "
                         f"to {GROUP_RTOL:.0e} relative (ball arithmetic: {rel[i, j]:.1e}; "
                         f"c_g/c_T = {G[i, j]:.3e})"))


def _eigen_fallback(patch, kappa, block, group, idx, W, G, share, failures, route):
    """The float eigen-solver (and extended precision where it is not accurate) at ``idx``."""
    mixed = block.kind is None
    k = kappa[idx]
    route[idx] = 1
    try:
        Wf, X, M, err = _eigen_block(patch, k, block, group or mixed)
    except (np.linalg.LinAlgError, InputError) as exc:
        for kk in k:
            failures.append(("omega", float(kk), f"float eigen-solver failed ({exc})"))
        if W is None:
            W = np.full((kappa.size, 2 * patch.n - len(block.massless)
                         if block.E is None else block.E.shape[1] - len(block.massless)), np.nan)
        W[idx] = np.nan
        return W, G, share
    Gf = None
    if group:
        dK, dM = pencil_derivative(patch, None, k)
        if block.E is not None:
            dK, dM = congruence(block.E.T, dK), congruence(block.E.T, dM)
        Gf = _slopes(Wf, X, dK, dM, M)
    basis = block.E
    refine = np.any(err > RTOL, axis=1) & (k > 0)  # as refine_inaccurate
    route[idx[refine]] = 2
    Wf = refine_inaccurate(patch, None, k, Wf, basis, Gf, failures, err, RTOL)
    if W is None:
        W = np.empty((kappa.size, Wf.shape[1]))
        G = np.empty_like(W) if group else None
        share = np.empty_like(W) if mixed else None
    W[idx] = Wf
    if group:
        G[idx] = Gf
    if mixed:
        share[idx] = _parity_from_vectors(patch, X)
    return W, G, share


def _tiny(kappa, W0, W1, G0, G1, failures):
    """Branches at kappa < KAPPA_TINY from their values at KAPPA_TINY and 2 KAPPA_TINY."""
    with np.errstate(all="ignore"):
        e = np.log2(W1 / W0)
    e = np.where(np.isfinite(e), e, np.nan)
    ei = np.rint(e)
    bad = ~(np.abs(e - ei) < 1e-6)
    t = (kappa / KAPPA_TINY)[:, None]
    with np.errstate(all="ignore"):
        W = W0 * t**ei
        G = None
        if G0 is not None:
            G = G0 * t ** np.where(ei >= 1, ei - 1, 1)
    for i, kk in enumerate(kappa):
        under = (W[i] < np.finfo(float).tiny) & (ei > 0) & (kk > 0)
        if np.any(bad) or np.any(under):
            why = "leading power law not found" if np.any(bad) else \
                f"Omega ~ kappa^{int(np.max(ei[under]))} underflows float64 at this kappa"
            failures.append(("omega", float(kk), why))
            W[i, bad | under] = np.nan
    return W, G


def _branches_block(patch: PlatePatch, kappa: np.ndarray, group: bool = False,
                    plan=None, failures=None):
    plan = _plan(patch, None) if plan is None else plan
    failures = [] if failures is None else failures
    tiny = kappa < KAPPA_TINY
    main = np.flatnonzero(~tiny)
    ref = np.array([KAPPA_TINY, 2 * KAPPA_TINY])
    omega, symmetry, slopes = {}, {}, {}
    results = []
    route = np.zeros(kappa.size, dtype=np.int8)
    for block in plan:
        parts = {}
        if main.size:
            parts["main"] = _solve_block(patch, kappa[main], block, group, failures)
        if np.any(tiny):
            # the power laws below KAPPA_TINY are read at two reference kappa; what cannot be
            # certified there is reported at the kappa asked for
            ref_fail = []
            parts["ref"] = _solve_block(patch, ref, block, group, ref_fail)
            seen = set()
            for what, k_ref, why in ref_fail:
                if what not in seen:  # one entry per quantity and kappa
                    seen.add(what)
                    failures.extend((what, float(k), f"{why} (at the power-law reference "
                                     f"kappa {k_ref:.0e})") for k in kappa[tiny])
        cols = next(iter(parts.values()))[0].shape[1]
        Wf = np.empty((kappa.size, cols))
        Gf = np.empty_like(Wf) if group else None
        Sf = np.empty_like(Wf) if block.kind is None else None
        if main.size:
            W, G, share, r_main = parts["main"]
            route[main] = np.maximum(route[main], r_main)
            Wf[main] = W
            if group:
                Gf[main] = G
            if Sf is not None:
                Sf[main] = share
        if np.any(tiny):
            W, G, share, _ = parts["ref"]
            route[tiny] = ROUTES.index("power law")
            Wt, Gt = _tiny(kappa[tiny], W[0], W[1], None if G is None else G[0],
                           None if G is None else G[1], failures)
            Wf[tiny] = Wt
            if group:
                Gf[tiny] = Gt
            if Sf is not None:
                Sf[tiny] = share[0]
        results.append((block, Wf, Gf, Sf))
    for block, W, G, share in results:
        if block.kind is not None:
            for j in range(W.shape[1]):
                label = f"{block.kind}{j}"
                omega[label], symmetry[label] = W[:, j], block.kind
                if group:
                    slopes[label] = G[:, j]
            continue
        # parity of each mode shape: its share in the symmetric mirror subspace of the patch
        is_s = share >= 0.5
        rank_s = np.cumsum(is_s, axis=1) - 1
        rank_a = np.cumsum(~is_s, axis=1) - 1
        # the column of the j-th root of each parity in every row (an index past the end,
        # then NaN, where a row has fewer)
        R = W.shape[1]
        Wn = np.concatenate([W, np.full((W.shape[0], 1), np.nan)], axis=1)
        Gn = np.concatenate([G, np.full((G.shape[0], 1), np.nan)], axis=1) if group else None
        rows = np.arange(W.shape[0])
        for kind, mask, rank in (("S", is_s, rank_s), ("A", ~is_s, rank_a)):
            count = mask.sum(axis=1)
            for j in range(int(count.max(initial=0))):
                col = np.argmax(mask & (rank == j), axis=1)
                col[count <= j] = R
                label = f"{kind}{j}"
                omega[label], symmetry[label] = Wn[rows, col], "mixed"
                if group:
                    slopes[label] = Gn[rows, col]
    return omega, symmetry, slopes, route


def fundamental_branches(patch: PlatePatch, nu, kappa) -> dict[str, np.ndarray]:
    """Discrete S0 and A0 at ``kappa``: the labels of :func:`discrete_branches` (one rule).

    >>> from dispersion.symbolic.plate import plate_patch
    >>> sorted(fundamental_branches(plate_patch(mass="singular"), 0.3, [0.1]))
    ['A0', 'S0']
    """
    patch = with_nu(patch, nu)
    br = discrete_branches(patch, None, kappa)
    return {label: br.omega[label] for label in ("S0", "A0")}
