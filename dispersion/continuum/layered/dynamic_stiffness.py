"""The exact dispersion relation of a layered plate: its dynamic stiffness, counted and signed.

Each layer is cut into sublayers thin enough that none of them, clamped on both faces, has a
mode below the frequency (:func:`sublayers`); a sublayer's dynamic stiffness, relating the
forces on its faces to their displacements, follows from its transfer matrix
:math:`P = e^{A t}` (:mod:`dispersion.continuum.layered.stroh`),

.. math::

    \\begin{bmatrix} -T_0 \\\\ T_1 \\end{bmatrix} =
    \\begin{bmatrix} P_{ut}^{-1} P_{uu} & -P_{ut}^{-1} \\\\
    P_{tu} - P_{tt} P_{ut}^{-1} P_{uu} & P_{tt} P_{ut}^{-1} \\end{bmatrix}
    \\begin{bmatrix} U_0 \\\\ U_1 \\end{bmatrix},

and the plate's stiffness :math:`K(\\kappa, \\Omega)` is their assembly (with spring
interfaces as massless springs), block tridiagonal. A free plate has a mode at
:math:`(\\kappa, \\Omega)` exactly where K is singular, and -- because no sublayer has a
clamped mode below :math:`\\Omega` -- K has no poles and, for an undamped plate, is Hermitian
with

.. math::

    N(\\kappa, \\Omega) = \\#\\{\\text{negative eigenvalues of } K(\\kappa, \\Omega)\\}
    = \\#\\{\\text{modes of the plate at } \\kappa \\text{ below } \\Omega\\}

(the Wittrick-Williams count with no clamped-member term), and
:math:`\\operatorname{sign} \\det K = (-1)^N`. The count is read from the block
:math:`LDL^H` factorisation (Sylvester's law of inertia over the Schur complements), in
:math:`O(\\text{sublayers})` work; so is the determinant.

A :class:`ModeClass` restricts K to the displacements of one family (Lamb :math:`u_1, u_3`
or SH :math:`u_2` where they are apart) and, for a symmetric stack, to the upper half with
the mid-plane conditions of symmetric or antisymmetric modes: each class is counted alone,
which names its modes (S_j, A_j, SH_n, as in the Rayleigh-Lamb code).

:func:`det_ball` evaluates the same determinant in ball arithmetic (python-flint), so the
sign of :math:`\\det K` -- and with it a sign change that encloses a root -- is certain.

References
----------
W. H. Wittrick, F. W. Williams, "A general algorithm for computing natural frequencies of
elastic structures", Q. J. Mech. Appl. Math. 24 (1971) 263; S. I. Rokhlin, L. Wang, "Stable
recursive algorithm for elastic wave propagation in layered anisotropic media: stiffness
matrix method", JASA 112 (2002) 822; E. V. Haynsworth, "Determination of the inertia of a
partitioned Hermitian matrix", Linear Algebra Appl. 1 (1968) 73.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.continuum.layered.stroh import system_derivatives, system_matrix, system_parts

__all__ = ["ModeClass", "mode_classes", "Element", "class_stack", "sublayers", "element_stiffness",
           "count_and_det", "assemble", "null_vector", "det_ball", "SUBLAYER_MARGIN", "SUBLAYER_KT"]

#: A sublayer is at most this fraction of the thickness at which its clamped modes could reach
#: the frequency (the rigorous bound of :func:`sublayers`): the stiffness stays far from its
#: poles.
SUBLAYER_MARGIN = 0.5
#: ... and at most this many units of 1/|kappa| thick: the evanescent factors
#: :math:`e^{\\pm\\kappa t}` of one sublayer stay below e^2, so the float stiffness keeps its
#: digits.
SUBLAYER_KT = 2.0


@dataclass(frozen=True)
class ModeClass:
    """One family of modes counted alone.

    ``name`` (S, A, SHS, SHA, L, SH, M), ``dofs`` (displacement components kept, 0 = u1,
    1 = u2, 2 = u3), ``half`` (the upper half of a symmetric stack), ``mid_fixed`` (components
    held at zero on the mid-plane) and ``prefix``/``step``/``offset`` of the mode names
    (mode j is ``prefix + str(step * j + offset)``).
    """

    name: str
    dofs: tuple
    half: bool = False
    mid_fixed: tuple = ()
    prefix: str = ""
    step: int = 1
    offset: int = 0
    family: str = ""

    def label(self, j: int) -> str:
        return f"{self.prefix}{self.step * j + self.offset}"


def mode_classes(plate) -> tuple[ModeClass, ...]:
    """The classes of a :class:`~dispersion.continuum.layered.layered_plate.LayeredPlate`:

    ======================  =================================================
    symmetric, decoupled    S, A (Lamb), SH_0, SH_2, ... and SH_1, SH_3, ...
    symmetric, coupled      S, A (every polarisation)
    decoupled               L_0, L_1, ... (Lamb) and SH_0, SH_1, ...
    neither                 M_0, M_1, ...
    ======================  =================================================

    >>> from dispersion.continuum.layered.layered_plate import laminate
    >>> from dispersion.materials.materials import ply
    >>> [c.name for c in mode_classes(laminate("[0/90]s", ply("T800/913"), 0.125))]
    ['S', 'A', 'SHS', 'SHA']
    >>> [c.name for c in mode_classes(laminate("[0/90]s", ply("T800/913"), 0.125, direction=30))]
    ['S', 'A']
    """
    sym, dec = plate.symmetric, plate.decoupled
    if sym and dec:
        return (ModeClass("S", (0, 2), True, (2,), "S", family="S"),
                ModeClass("A", (0, 2), True, (0,), "A", family="A"),
                ModeClass("SHS", (1,), True, (), "SH", 2, 0, family="SH"),
                ModeClass("SHA", (1,), True, (1,), "SH", 2, 1, family="SH"))
    if sym:
        return (ModeClass("S", (0, 1, 2), True, (2,), "S", family="S"),
                ModeClass("A", (0, 1, 2), True, (0, 1), "A", family="A"))
    if dec:
        return (ModeClass("L", (0, 2), prefix="L", family="L"),
                ModeClass("SH", (1,), prefix="SH", family="SH"))
    return (ModeClass("M", (0, 1, 2), prefix="M", family="M"),)


@dataclass(frozen=True)
class Element:
    """A run of ``count`` equal sublayers of layer ``layer`` (thickness ``t`` each), or
    (``layer`` = -1) the springs of interface ``interface`` (``scale`` 2: a mid-plane spring
    seen from one half)."""

    layer: int
    t: float = 0.0
    count: int = 1
    interface: int = -1
    scale: float = 1.0


def _kelvin_min(C: np.ndarray) -> float:
    w = np.array([1, 1, 1, math.sqrt(2), math.sqrt(2), math.sqrt(2)])
    return float(np.linalg.eigvalsh(C.real * w[:, None] * w[None, :])[0])


def class_stack(stack, cls: ModeClass):
    """The layers a class is solved on, from the bottom face (or, for a half class, from
    the mid-plane) up: ``(rows, springs_above, mid_spring)``, rows of ``(layer, thickness)``
    (an odd stack's middle layer enters with half its thickness), ``springs_above[n]`` the
    interface index with springs above row n (None: perfect or the top face), and the
    interface with springs on the mid-plane (None without)."""
    L = len(stack.thickness)
    mid_spring = None
    if cls.half:
        c = L // 2
        if L % 2:
            rows = [(c, stack.thickness[c] / 2)] + [(i, stack.thickness[i])
                                                    for i in range(c + 1, L)]
        else:
            rows = [(i, stack.thickness[i]) for i in range(c, L)]
            if np.isfinite(stack.springs[c - 1]).all():
                mid_spring = c - 1
    else:
        rows = [(i, stack.thickness[i]) for i in range(L)]
    above = [i if n + 1 < len(rows) and np.isfinite(stack.springs[i]).all() else None
             for n, (i, _) in enumerate(rows)]
    return rows, above, mid_spring


def sublayers(stack, cls: ModeClass, omega_max: float, kappa_max: float) -> tuple:
    """The elements (bottom up; from the mid-plane up for a half class) for frequencies up
    to ``omega_max`` and :math:`|\\kappa|` up to ``kappa_max``.

    A sublayer of thickness t clamped on both faces has no mode below
    :math:`\\Omega^2 = \\lambda_{min} (\\kappa^2 + \\pi^2 / t^2) / (2\\rho)`
    (:math:`\\lambda_{min}`: smallest Kelvin eigenvalue of C; Korn's equality
    :math:`2\\int \\bar\\varepsilon : \\varepsilon = \\int \\nabla\\bar u : \\nabla u +
    \\int |\\nabla \\cdot u|^2` for fields zero on both faces, then Poincare's inequality),
    so t is at most :data:`SUBLAYER_MARGIN` of :math:`\\pi\\sqrt{\\lambda_{min}/(2\\rho)} /
    \\Omega_{max}`, and at most :data:`SUBLAYER_KT` / kappa_max.
    """
    rows, above, mid_spring = class_stack(stack, cls)
    elements = []
    if mid_spring is not None:
        elements.append(Element(-1, interface=mid_spring, scale=2.0))
    for (i, thick), face in zip(rows, above):
        lam = _kelvin_min(stack.C[i])
        t_max = SUBLAYER_MARGIN * math.pi * math.sqrt(lam / (2 * stack.rho[i])) / max(
            omega_max, 1e-300)
        if kappa_max > 0:
            t_max = min(t_max, SUBLAYER_KT / kappa_max)
        count = max(1, math.ceil(thick / t_max))
        elements.append(Element(i, thick / count, count))
        if face is not None:
            elements.append(Element(-1, interface=face))
    return tuple(elements)


#: Taylor terms of the matrix exponential after scaling to norm <= 1/2: the truncation
#: 0.5^19 / 19! is below 1e-23, far under double rounding.
_TAYLOR_TERMS = 18   # a multiple of 3 (the Paterson-Stockmeyer chunks of _transfer)
_TAYLOR = [1.0 / math.factorial(j) for j in range(_TAYLOR_TERMS + 1)]


def _transfer(A: np.ndarray, t) -> np.ndarray:
    """:math:`e^{A t}` for a stack of 6x6 matrices (``t`` a number or an array that
    broadcasts against the stack's leading axes): scaling and squaring with the Taylor
    polynomial of degree :data:`_TAYLOR_TERMS`, evaluated by the Paterson-Stockmeyer scheme
    (8 products instead of 18; vectorised over the stack, where scipy's expm loops in
    Python)."""
    X = A * np.asarray(t)[..., None, None]
    norm = np.max(np.sum(np.abs(X), axis=-1), axis=-1)   # infinity norm of each
    s = np.maximum(0, np.ceil(np.log2(np.maximum(norm, 1e-300) / 0.5))).astype(int)
    X = X / (2.0 ** s)[..., None, None]
    eye = np.eye(X.shape[-1])
    X2 = X @ X
    X3 = X2 @ X
    c = _TAYLOR
    # sum_j X^j / j! = sum_i X3^i (c[3i] + c[3i+1] X + c[3i+2] X2), Horner in X3
    E = np.broadcast_to(c[_TAYLOR_TERMS] * eye, X.shape)
    for i in range(_TAYLOR_TERMS // 3 - 1, -1, -1):
        E = c[3 * i] * eye + c[3 * i + 1] * X + c[3 * i + 2] * X2 + X3 @ E
    for q in range(int(s.max(initial=0))):
        more = s > q
        if np.all(more):
            E = E @ E
        else:
            E[more] = E[more] @ E[more]
    return E


def element_stiffness(stack, element: Element, kappa, omega, derivatives: bool = False):
    """The 6x6 stiffness (blocks: bottom, top face) of one sublayer or spring element at
    each ``kappa`` (array), shape ``kappa.shape + (6, 6)``; with ``derivatives`` also its
    derivatives in kappa and Omega."""
    kappa = np.asarray(kappa, dtype=complex)
    shape = kappa.shape + (6, 6)
    if element.layer < 0:
        ks = np.diag(stack.springs[element.interface] * element.scale)
        K = np.zeros(shape, dtype=complex)
        K[..., :3, :3] = ks
        K[..., 3:, 3:] = ks
        K[..., :3, 3:] = -ks
        K[..., 3:, :3] = -ks
        if derivatives:
            return K, np.zeros(shape, complex), np.zeros(shape, complex)
        return K
    C, rho = stack.C[element.layer], stack.rho[element.layer]
    A = system_matrix(C, rho, kappa, omega, _parts_of(stack, element.layer))
    t = element.t
    if derivatives:
        # the derivative of e^(A t) along E is the upper right block of
        # e^([[A, E], [0, A]] t) (Van Loan 1978)
        dAk, dAw = system_derivatives(C, rho, kappa, omega)
        out = []
        for dA in (dAk, dAw):
            big = np.zeros(shape[:-2] + (12, 12), dtype=complex)
            big[..., :6, :6] = A
            big[..., 6:, 6:] = A
            big[..., :6, 6:] = dA
            out.append(_transfer(big, t))
        P, dPk, dPw = out[0][..., :6, :6], out[0][..., :6, 6:], out[1][..., :6, 6:]
    else:
        P = _transfer(A, t)
    K = _from_transfer(P)
    if not derivatives:
        return K
    return K, _from_transfer_derivative(P, dPk), _from_transfer_derivative(P, dPw)


def _parts_of(stack, layer: int):
    """The layer's :func:`~dispersion.continuum.layered.stroh.system_parts` (kept by the
    stack once computed; a stack without them gets them computed here)."""
    parts = getattr(stack, "parts", None)
    return None if parts is None else parts[layer]


def _layer_stiffness(stack, layer_elements, kappa, omega, comps=(0, 1, 2)):
    """The stiffness of several sublayers at once, ``(len(layer_elements),) + kappa.shape +
    (2m, 2m)`` for the m displacement components ``comps`` (and their tractions): one
    batched transfer matrix for all of them. With fewer than three components the layers
    must not couple them to the others (a decoupled class): the exponential is then taken of
    the smaller system, which is exact."""
    kappa = np.asarray(kappa, dtype=complex)
    parts = np.array([system_parts(stack.C[e.layer], stack.rho[e.layer])
                      if _parts_of(stack, e.layer) is None else _parts_of(stack, e.layer)
                      for e in layer_elements])
    idx = np.array(list(comps) + [3 + c for c in comps])
    parts = parts[..., idx[:, None], idx[None, :]]
    lead = (len(layer_elements),) + (1,) * kappa.ndim
    P = parts.reshape(lead + parts.shape[-3:])
    k = kappa[None, ..., None, None]
    w2 = np.asarray(omega, dtype=complex) ** 2
    w2 = w2[None, ..., None, None] if w2.ndim else w2
    A = P[..., 0, :, :] + k * (P[..., 1, :, :] + k * P[..., 2, :, :]) + w2 * P[..., 3, :, :]
    t = np.array([e.t for e in layer_elements]).reshape(lead)
    return _from_transfer(_transfer(A, t))


def _from_transfer(P):
    m = P.shape[-1] // 2
    Puu, Put, Ptu, Ptt = P[..., :m, :m], P[..., :m, m:], P[..., m:, :m], P[..., m:, m:]
    X = np.linalg.inv(Put)
    XP = X @ Puu
    K = np.empty(P.shape, dtype=complex)
    K[..., :m, :m] = XP
    K[..., :m, m:] = -X
    K[..., m:, :m] = Ptu - Ptt @ XP
    K[..., m:, m:] = Ptt @ X
    return K


def _from_transfer_derivative(P, dP):
    Puu, Put, Ptt = P[..., :3, :3], P[..., :3, 3:], P[..., 3:, 3:]
    dPuu, dPut, dPtu, dPtt = dP[..., :3, :3], dP[..., :3, 3:], dP[..., 3:, :3], dP[..., 3:, 3:]
    X = np.linalg.inv(Put)
    dX = -X @ dPut @ X
    dK = np.empty(P.shape, dtype=complex)
    dK[..., :3, :3] = dX @ Puu + X @ dPuu
    dK[..., :3, 3:] = -dX
    dK[..., 3:, :3] = dPtu - dPtt @ X @ Puu - Ptt @ dX @ Puu - Ptt @ X @ dPuu
    dK[..., 3:, 3:] = dPtt @ X + Ptt @ dX
    return dK


def _mid(stack, cls: ModeClass, elements):
    """``(chain, first, ground)``: the sublayers one by one, the components kept at the
    first node and, for a symmetric stack with springs on its mid-plane, the grounding
    stiffness there (the mirror image moves the components that are odd in the class by
    the opposite amount: a jump of twice their value, so twice the springs; None without)."""
    chain = list(_chain(elements))
    dofs = list(cls.dofs)
    if chain and chain[0][0].layer < 0 and chain[0][0].scale != 1.0:
        ks = stack.springs[chain[0][0].interface]
        ground = np.diag([2 * ks[d] if d in cls.mid_fixed else 0.0 for d in dofs])
        return chain[1:], dofs, ground
    first = [d for d in dofs if d not in cls.mid_fixed] if cls.half else dofs
    return chain, first, None


def _chain(elements):
    """Elements one sublayer at a time: ``(element, first)``; ``first`` marks where a run
    starts (its stiffness is computed once per run)."""
    for e in elements:
        for n in range(e.count):
            yield e, n == 0


def count_and_det(stack, cls: ModeClass, elements, kappa, omega):
    """``(N, log|det K|, sign det K)`` of the class's stiffness at each ``kappa`` (1-d
    array) and one ``omega``: N the number of negative eigenvalues (undamped: the number of
    the class's modes below omega at that kappa), the determinant from the block
    factorisation; for a damped plate N is meaningless and ``sign`` is complex.

    The stiffness of every distinct sublayer is computed in one batch; the pivots of the
    factorisation are collected and their inertia and determinants taken in one batch at
    the end (the elimination itself runs node by node)."""
    kappa = np.atleast_1d(np.asarray(kappa, dtype=float if np.isrealobj(kappa) else complex))
    n = kappa.size
    chain, first, ground = _mid(stack, cls, elements)
    # the class's components only: a class of fewer than three is decoupled from the rest
    m = len(cls.dofs)
    dofs = np.arange(m)
    first = np.array([cls.dofs.index(d) for d in first], dtype=int)
    sel = np.array(list(cls.dofs) + [3 + d for d in cls.dofs])
    hermitian = stack.lossless and np.isrealobj(kappa)
    distinct = list(dict.fromkeys(e for e, _ in chain))
    layers = [e for e in distinct if e.layer >= 0]
    stiff = dict(zip(layers, _layer_stiffness(stack, layers, kappa, omega, cls.dofs))) \
        if layers else {}
    for e in distinct:
        if e.layer < 0:
            stiff[e] = element_stiffness(stack, e, kappa, omega)[..., sel[:, None], sel[None, :]]
    pivots = {}   # size -> pivot blocks, their inertia and determinants taken at the end
    S = None
    rows = first
    for e, _ in chain:
        K = stiff[e]
        K00 = K[:, :m, :m][:, rows[:, None], rows[None, :]]
        if rows.size == 0:   # the first node has no unknowns (all held on the mid-plane)
            S = K[:, m:, m:]
            rows = dofs
            continue
        if S is None:
            S = K00 + (0 if ground is None else ground)
        else:
            S = S + K00
        # eliminate the bottom node of this element
        pivots.setdefault(S.shape[-1], []).append(S)
        K01 = K[:, :m, m:][:, rows, :]
        K10 = K[:, m:, :m][:, :, rows]
        S = K[:, m:, m:] - K10 @ _solve(S, K01)
        rows = dofs
    pivots.setdefault(S.shape[-1], []).append(S)
    count = np.zeros(n, dtype=int)
    logdet = np.zeros(n)
    sign = np.ones(n, dtype=float if hermitian else complex)
    for blocks in pivots.values():
        _pivot(np.stack(blocks), hermitian, count, logdet, sign)
    return count, logdet, sign


def _solve(S, B):
    """``S^-1 B`` for a stack of pivots; a pivot that is singular to working precision (a
    point exactly on a partial stack's clamped mode, a set of measure zero) is moved by
    1e-15 of its norm, which moves det K by as little."""
    try:
        return np.linalg.solve(S, B)
    except np.linalg.LinAlgError:
        scale = np.maximum(np.max(np.abs(S), axis=(-1, -2), keepdims=True),
                           np.max(np.abs(B), axis=(-1, -2), keepdims=True))
        return np.linalg.solve(S + 1e-15 * scale * np.eye(S.shape[-1]), B)


def _pivot(S, hermitian, count, logdet, sign):
    """Add the inertia and determinants of the pivots ``S`` (shape ``(pivots, n, m, m)``)
    to ``count``, ``logdet`` and ``sign`` (shape ``(n,)``)."""
    if hermitian:
        lam = np.linalg.eigvalsh((S + np.conj(np.swapaxes(S, -1, -2))) / 2)
        count += np.count_nonzero(lam < 0, axis=(0, -1))
        with np.errstate(divide="ignore"):
            logdet += np.sum(np.log(np.abs(lam)), axis=(0, -1))
        sign *= np.prod(np.sign(lam), axis=(0, -1))
    else:
        s, ld = np.linalg.slogdet(S)
        logdet += np.sum(ld, axis=0)
        sign *= np.prod(s, axis=0)


def assemble(stack, cls: ModeClass, elements, kappa: float, omega: float,
             derivatives: bool = False, sparse: bool = False):
    """The class's stiffness as one matrix at one ``(kappa, omega)`` (and its kappa and
    Omega derivatives): for null vectors, group velocities and mode shapes. Unknowns: the
    kept components at each node, bottom (mid-plane) up. Dense, or with ``sparse`` a scipy
    CSC matrix (block tridiagonal)."""
    dofs = list(cls.dofs)
    chain, first, ground = _mid(stack, cls, elements)
    sizes = [len(first)] + [len(dofs)] * len(chain)
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    N = int(offsets[-1])
    distinct = list(dict.fromkeys(e for e, _ in chain))
    blocks = {}
    for e in distinct:
        out = element_stiffness(stack, e, np.array([kappa]), omega, derivatives)
        blocks[e] = [M[0] for M in (out if derivatives else (out,))]
    rows = []
    vals = [[] for _ in range(3 if derivatives else 1)]
    cols = []
    sel_b = np.array(dofs, dtype=int)
    for j, (e, _) in enumerate(chain):
        sel_a = np.array(first if j == 0 else dofs, dtype=int)
        local = np.concatenate([sel_a, 3 + sel_b])
        glob = np.concatenate([offsets[j] + np.arange(sel_a.size),
                               offsets[j + 1] + np.arange(sel_b.size)])
        rows.append(np.repeat(glob, glob.size))
        cols.append(np.tile(glob, glob.size))
        for v, K in zip(vals, blocks[e]):
            v.append(K[np.ix_(local, local)].ravel())
    if ground is not None:
        g = np.arange(len(first))
        rows.append(np.repeat(g, g.size))
        cols.append(np.tile(g, g.size))
        vals[0].append(np.asarray(ground, dtype=complex).ravel())
        for v in vals[1:]:
            v.append(np.zeros(g.size * g.size, dtype=complex))
    import scipy.sparse as sp

    r, c = np.concatenate(rows), np.concatenate(cols)
    mats = [sp.csc_matrix((np.concatenate(v), (r, c)), shape=(N, N)) for v in vals]
    if not sparse:
        mats = [M.toarray() for M in mats]
    return tuple(mats) if derivatives else mats[0]


def null_vector(K) -> np.ndarray:
    """The null vector of a (sparse) stiffness at a root, normalised to unit length: two
    steps of inverse iteration with a shift of 1e-12 of its largest entry (a root certified
    to 1e-12 leaves K singular to about that)."""
    import scipy.sparse as sp
    from scipy.sparse.linalg import splu

    K = sp.csc_matrix(K)
    n = K.shape[0]
    shift = 1e-12 * max(float(abs(K).max()), 1e-300)
    lu = splu((K - shift * sp.identity(n, dtype=complex, format="csc")).tocsc())
    v = np.cos(np.arange(n) + 0.5) + 0j    # not orthogonal to any vector by accident
    for _ in range(2):
        v = lu.solve(v)
        v /= np.linalg.norm(v)
    return v


# ---------------------------------------------------------------- ball arithmetic

def _acb_expm_stiffness(stack, element: Element, kappa, omega, prec: int):
    import flint

    C, rho = stack.C[element.layer], stack.rho[element.layer]
    from dispersion.continuum.layered.stroh import q_blocks

    Qxx, Qxz, Qzz = (flint.acb_mat([[flint.acb(float(v.real), float(v.imag)) for v in row]
                                    for row in Q]) for Q in q_blocks(C))
    Zi = Qzz.inv()
    Qzx = Qxz.transpose()
    k = kappa
    ik = flint.acb(0, 1) * k
    R = Qxx - Qxz * Zi * Qzx
    w2 = flint.acb(omega) ** 2
    r = flint.acb(float(rho))
    top_left = -(ik * (Zi * Qzx))
    bottom_left = k * k * R - r * w2 * flint.acb_mat(3, 3, [1, 0, 0, 0, 1, 0, 0, 0, 1])
    bottom_right = -(ik * (Qxz * Zi))
    A = flint.acb_mat(6, 6)
    for i in range(3):
        for j in range(3):
            A[i, j] = top_left[i, j]
            A[i, j + 3] = Zi[i, j]
            A[i + 3, j] = bottom_left[i, j]
            A[i + 3, j + 3] = bottom_right[i, j]
    P = (A * flint.acb(element.t)).exp()

    def block(r0, c0):
        return flint.acb_mat([[P[r0 + i, c0 + j] for j in range(3)] for i in range(3)])

    Puu, Put, Ptu, Ptt = block(0, 0), block(0, 3), block(3, 0), block(3, 3)
    X = Put.inv()
    XP = X * Puu
    return XP, -X, Ptu - Ptt * XP, Ptt * X, Put


def det_ball(stack, cls: ModeClass, elements, kappa, omega: float, prec: int = 160,
             entire: bool = False):
    """:math:`\\det K(\\kappa, \\Omega)` of the class, enclosed in ball arithmetic
    (python-flint ``acb``, ``prec`` bits): the float data of the plate, kappa (real or
    complex) and Omega taken as exact binary numbers. Returns the ``acb`` ball (real for an
    undamped plate at a real kappa). ``entire``: times :math:`\\det P_{ut}` of every
    sublayer (its block of the class's components), which clears the poles of K, so the
    product is an entire function of kappa whose zeros are the modes of the class (counted
    in a disc or a rectangle by the argument principle)."""
    import flint

    old = flint.ctx.prec
    flint.ctx.prec = prec
    try:
        dofs = list(cls.dofs)
        chain, first, g = _mid(stack, cls, elements)
        kap = flint.acb(float(np.real(kappa)), float(np.imag(kappa)))
        cache = {}

        def stiff(e):
            if e not in cache:
                if e.layer < 0:
                    ks = stack.springs[e.interface] * e.scale
                    D = flint.acb_mat([[flint.acb(float(ks[i])) if i == j else 0
                                        for j in range(3)] for i in range(3)])
                    cache[e] = (D, -D, -D, D, None)
                else:
                    cache[e] = _acb_expm_stiffness(stack, e, kap, float(omega), prec)
            return cache[e]

        def sub(M, rows, cols):
            return flint.acb_mat([[M[i, j] for j in cols] for i in rows])

        ground = None if g is None else flint.acb_mat(
            [[flint.acb(float(v)) for v in row] for row in g])
        det = flint.acb(1)
        S = None
        rows = first
        for e, _ in chain:
            K00, K01, K10, K11, Put = stiff(e)
            if entire and Put is not None:
                # the class's block of P_ut only: its zeros are the poles of the class's K (a
                # decoupled class's other block would add zeros that are no modes)
                det *= sub(Put, dofs, dofs).det()
            if not rows:   # the first node has no unknowns
                S = sub(K11, dofs, dofs)
                rows = dofs
                continue
            block = sub(K00, rows, rows)
            S = (block + ground if ground is not None else block) if S is None else S + block
            ground = None
            det *= S.det()
            S = sub(K11, dofs, dofs) - sub(K10, dofs, rows) * S.solve(sub(K01, rows, dofs))
            rows = dofs
        det *= S.det()
        return det
    finally:
        flint.ctx.prec = old
