"""Every propagating Lamb and SH mode at a given frequency: the real roots in kappa, certified.

At a fixed :math:`\\Omega = \\omega h / c_T` the real wavenumbers :math:`\\kappa = kh \\ge 0` of
each symmetry class are the roots of the deflated Rayleigh-Lamb function
:math:`G(\\kappa, \\Omega)` (:func:`dispersion.continuum.deflated_frequency.deflated_with_noise`,
sampled with a bound on its rounding error). They are found and *counted* by the argument of
the kappa tracer (:mod:`dispersion.continuum.exact_branches`), turned on its side:

1. **Count at fixed kappa.** At each :math:`\\kappa` the class is a self-adjoint problem in
   :math:`\\Omega^2`; :math:`N(\\kappa, \\Omega)`, the number of its branches below
   :math:`\\Omega`, changes by one at each simple root, so the sign of G is
   :math:`\\sigma(\\kappa)(-1)^{N}` with :math:`\\sigma = \\operatorname{sign} G(\\kappa, 0)`.
2. **Both ends known.** :math:`N(0, \\Omega)` is the number of cut-offs below
   :math:`\\Omega` (closed form, :func:`~dispersion.continuum.rayleigh_lamb.cutoff_frequencies`).
   At a :math:`\\kappa_{hi} > \\Omega` only S0 and A0 can lie below :math:`\\Omega` (no
   higher mode is slower than :math:`c_T`: Mindlin 1960; Achenbach 1973, sec. 6.9), so
   :math:`N(\\kappa_{hi}, \\Omega) \\in \\{0, 1\\}` is read from the sign of G; kappa_hi is
   raised until it is 0 (S0 and A0 rise with kappa, so no root lies beyond).
3. **Every root accounted for.** Brackets are certain sign changes on a kappa grid of
   spacing ``step`` that also holds the kappa of every zero-group-velocity point (a branch
   that turns, such as S1 between its ZGV point and its cut-off, gives two roots on either
   side of it, never in one cell); three same-signed samples dipping towards zero are
   refined as in the tracer. Walking up in kappa, each root with group velocity
   :math:`c_g` changes the count by :math:`-\\operatorname{sign} c_g`: the count before it
   names the branch (S_j, A_j in the tracer's order at that kappa) and the walk must end at
   :math:`N(\\kappa_{hi}) = 0`. Whatever does not add up is listed in ``failures``.
   A sample whose float sign lies within its rounding bound (kappa = 0 next to a cut-off, the
   ZGV kappa next to a ZGV frequency) has its sign decided in ball arithmetic.
4. **Every root certified.** Roots are closed by the Illinois method to ``rtol`` (where
   :math:`P < 0` makes G cosh-sized, polished on
   :func:`~dispersion.continuum.deflated_frequency.evanescent_frequency_function`) and each is
   certified to :data:`ROOT_RTOL` by a sign change of the *exact* frequency function at
   :math:`\\kappa (1 \\pm \\delta)`, :data:`ROOT_DELTA` (:mod:`dispersion.continuum.root_certificate`):
   in floats with a proven rounding bound, else in ball arithmetic, else closed again in
   ball arithmetic from its scan cell (next to a cut-off or a ZGV point the float root is
   off); what none of these certifies is listed in ``failures``. "Exact" means at the
   requested float :math:`\\Omega` and the exact Poisson ratio ``nu`` (a float is its binary
   value; a material passes the rational of its speeds,
   :attr:`~dispersion.materials.materials.Material.nu_exact`): within a relative distance
   :math:`\\delta_c` of a cut-off a root moves by :math:`1/(2\\delta_c)` times a relative
   change of either, so the float nearest to nu would not do.

SH modes come in closed form (:mod:`dispersion.continuum.sh`).

>>> r = modes_at_frequency(0.3, [1.0])
>>> [(lab, round(float(k), 10)) for lab, k in zip(r.label, r.kappa)]
[('S0', 0.5990758101), ('A0', 1.355012978), ('SH0', 1.0)]

References
----------
R. D. Mindlin, "Waves and vibrations in isotropic, elastic plates", in *Structural
Mechanics*, Pergamon 1960; J. D. Achenbach, *Wave propagation in elastic solids*, 1973, ch. 6;
C. Prada, D. Clorennec, D. Royer, J. Acoust. Soc. Am. 124 (2008) 203 (backward S1, ZGV).
"""
from __future__ import annotations

import numbers
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from dispersion.continuum.illinois import illinois
from dispersion.continuum.isotropic_plate import (ROOT_DELTA, ROOT_RTOL, SLOPE_OMEGA,
                                                  IsotropicPlate)
from dispersion.continuum.sh import at_cutoff
from dispersion.errors import InputError, check_nu, check_positive

__all__ = ["FREQUENCY_OMEGA_MAX", "FREQUENCY_OMEGA_MIN", "MAX_SCAN_SAMPLES", "SLOPE_OMEGA",
           "ROOT_RTOL", "ROOT_DELTA", "FrequencyRoots", "modes_at_frequency", "modes_of",
           "zgv_points_below"]

#: Smallest Omega accepted. Rule: the fundamental roots must stay above kappa = 1e-3, below
#: which the tracer itself leaves the frequency function for the series (round-off); S0 has
#: kappa = Omega / 1.69.. there, so Omega >= 2e-3 (fd >= about 0.002 MHz mm in metals).
FREQUENCY_OMEGA_MIN = 2e-3
#: Largest Omega accepted. Rule: the largest Omega at which the scan was seen free of
#: failures -- 1800 random (nu in [-0.5, 0.49], Omega <= 30) requests certified every root;
#: from Omega = 36 on (nu = 0.45) the deflated function's cancellation at kappa ~ Omega leaves
#: stretches within round-off (listed as failures). A scaled, cancellation-free frequency
#: function would lift this bound. Omega = 30 is fd = 30 c_T / pi (about 30 MHz mm in metals).
FREQUENCY_OMEGA_MAX = 30.0
#: Largest scan of one call (kappa samples over all frequencies). Rule: the tracer's bound
#: (about a minute of work at ~3 us per sample).
MAX_SCAN_SAMPLES = 20_000_000
#: A frequency within this relative distance of a ZGV point's (as the float ZGV tracer found
#: it) has the pair of roots next to it split at the extremum of F located in ball
#: arithmetic (:func:`_split_zgv_pairs`), not only at the ZGV point's kappa. Rule: the float
#: ZGV kappa was within 2e-14 relative of the 50-digit one at 20 points of random plates, and
#: the pair's half-width is about sqrt(d) relative (d: the distance): 1e-12 keeps the pair
#: found with a ZGV kappa a million times worse.
ZGV_SPLIT = 1e-12
#: Most scan samples of one class decided in ball arithmetic, per requested frequency. Rule:
#: 122 scans (random nu and Omega, next to cut-offs, a 100-frequency sweep) left at most 2
#: samples within the float bound per class, but 1e-16 from a ZGV frequency the dip
#: refinement leaves up to 20 (three ZGV points, 1e-16 to 1e-14 from them); three times that.
MAX_ARB_SAMPLES = 64


@dataclass(frozen=True)
class FrequencyRoots:
    """Propagating modes at each requested :math:`\\Omega` (dimensionless, units of h, c_T).

    One entry per root: ``index`` (into ``omega``), ``label`` (S_j, A_j, SH_n), ``kappa``
    and ``group`` (:math:`d\\Omega/d\\kappa = c_g/c_T`). Rows are ordered by frequency, then
    mode number, then S, A, SH, then kappa (a backward branch has two roots with one label).
    ``cutoffs`` maps every label with a cut-off at or below ``max(omega)`` to its Omega at
    :math:`\\kappa = 0`; ``zgv`` lists the zero-group-velocity points (label, kappa, Omega);
    ``failures`` holds ``(Omega, kind, reason)`` wherever a count did not certify the roots.
    """

    nu: float
    omega: np.ndarray
    index: np.ndarray
    label: tuple[str, ...]
    kappa: np.ndarray
    group: np.ndarray
    cutoffs: dict
    zgv: tuple
    failures: tuple
    #: ``(index into omega, label)`` of every mode whose cut-off *is* the requested
    #: frequency (:func:`dispersion.continuum.sh.at_cutoff`): kappa = 0, infinite phase
    #: velocity, not propagating, so not among the rows.
    at_cutoff: tuple = ()
    #: The exact Poisson ratio the roots are certified at (``nu`` is the float nearest to it):
    #: a material's comes from its speeds (:attr:`~dispersion.materials.materials.Material.nu_exact`).
    nu_exact: Fraction | None = None

    @property
    def phase(self) -> np.ndarray:
        """:math:`c_p / c_T = \\Omega / \\kappa` per root."""
        return self.omega[self.index] / self.kappa


def _exact(value) -> Fraction:
    """The exact rational value of a real number (a float's binary value, a Fraction as is)."""
    if isinstance(value, numbers.Rational):
        return Fraction(int(value.numerator), int(value.denominator))
    if getattr(value, "is_Rational", False):    # sympy
        return Fraction(int(value.p), int(value.q))
    return Fraction(float(value))


def _check_omegas(omega) -> np.ndarray:
    try:
        omega = np.atleast_1d(np.asarray(omega, dtype=float))
    except (TypeError, ValueError):
        raise InputError("Omega must be a 1-d array of finite numbers") from None
    if omega.ndim != 1 or omega.size == 0:
        raise InputError("Omega must be a non-empty 1-d array")
    bad = ~np.isfinite(omega) | (omega < FREQUENCY_OMEGA_MIN) | (omega > FREQUENCY_OMEGA_MAX)
    if np.any(bad):
        raise InputError(f"Omega = omega h / c_T must lie in [{FREQUENCY_OMEGA_MIN:g}, "
                         f"{FREQUENCY_OMEGA_MAX:g}], got {omega[bad][0]!r}")
    return omega


def _kappa_hi(model, kind: str, omega: np.ndarray, start: np.ndarray):
    """Smallest tried kappa_hi > Omega with N(kappa_hi, Omega) = 0, and the failures."""
    k = np.maximum(start, omega * (1 + 1e-6))
    todo = np.arange(omega.size)
    for _ in range(12):
        g, e = model.dispersion(kind, k[todo], omega[todo])
        g0, e0 = model.dispersion(kind, k[todo], np.zeros(todo.size))
        sure = (np.abs(g) > e) & (np.abs(g0) > e0)
        done = sure & (np.sign(g) == np.sign(g0))
        todo = todo[~done]
        if todo.size == 0:
            return k, []
        k[todo] *= 1.5
        if np.any(k[todo] > model.kappa_limit):
            break
    return k, [(float(omega[i]), kind, f"no kappa_hi <= {model.kappa_limit:g} with every "
                "branch above Omega") for i in todo]


class _Scan:
    """Samples (frequency index, kappa, G, rounding bound), sorted by (index, kappa)."""

    def __init__(self, model, kind, omega):
        self.model, self.kind, self.omega = model, kind, omega
        self.fi = np.zeros(0, int)
        self.k = self.g = self.e = np.zeros(0)

    def add(self, fi, k):
        g, e = self.model.dispersion(self.kind, k, self.omega[fi])
        fi, k = np.concatenate([self.fi, fi]), np.concatenate([self.k, k])
        g, e = np.concatenate([self.g, g]), np.concatenate([self.e, e])
        order = np.lexsort((k, fi))
        fi, k, g, e = fi[order], k[order], g[order], e[order]
        keep = np.concatenate([[True], (np.diff(k) != 0) | (np.diff(fi) != 0)])
        self.fi, self.k, self.g, self.e = fi[keep], k[keep], g[keep], e[keep]

    def certain(self):
        return np.flatnonzero(np.abs(self.g) > self.e)

    def decide_exactly(self):
        """Samples whose float sign is within the rounding bound decided by the model in
        exact arithmetic (:meth:`~dispersion.continuum.plate_model.PlateModel.decide`): next
        to a cut-off at kappa = 0, next to a ZGV point at its kappa. A decided sample keeps
        its sign with a magnitude just above its bound, so it counts as certain."""
        for i in np.flatnonzero(~(np.abs(self.g) > self.e))[:MAX_ARB_SAMPLES * self.omega.size]:
            sign = self.model.decide(self.kind, float(self.k[i]), float(self.omega[self.fi[i]]))
            if sign:
                self.g[i] = sign * max(2 * self.e[i], 1e-300)


def _refine_dips(scan: _Scan, max_depth: int):
    """Refine cells around three same-signed samples whose parabola dips to zero (as the
    tracer does in Omega): a hidden pair of roots shows as such a dip."""
    for _ in range(max_depth):
        c = scan.certain()
        fi, k, g = scan.fi[c], scan.k[c], scan.g[c]
        if g.size < 3:
            return
        same = (fi[1:-1] == fi[:-2]) & (fi[1:-1] == fi[2:])
        dip = same & (np.sign(g[:-2]) == np.sign(g[1:-1])) & (np.sign(g[2:]) == np.sign(g[1:-1]))
        dip &= (np.abs(g[1:-1]) <= np.abs(g[:-2])) & (np.abs(g[1:-1]) <= np.abs(g[2:]))
        j = np.flatnonzero(dip) + 1
        if j.size:
            k0, k1, k2 = k[j - 1], k[j], k[j + 1]
            d01 = (g[j] - g[j - 1]) / (k1 - k0)
            d12 = (g[j + 1] - g[j]) / (k2 - k1)
            c2 = (d12 - d01) / (k2 - k0)
            with np.errstate(divide="ignore", invalid="ignore"):
                kv = 0.5 * (k0 + k1) - d01 / (2 * c2)
                vertex = g[j - 1] + (kv - k0) * d01 + c2 * (kv - k0) * (kv - k1)
            suspect = ~np.isfinite(vertex) | (np.sign(vertex) != np.sign(g[j]))
            suspect |= np.abs(vertex) < 0.5 * np.abs(g[j])
            j = j[suspect]
            j = j[np.minimum(k1 - k0, k2 - k1)[suspect] > 64 * np.spacing(k[j])]
        if j.size == 0:
            return
        frac = np.linspace(0, 1, 9)[1:-1]
        new = np.concatenate([(k[j - 1][:, None] + frac * (k[j] - k[j - 1])[:, None]).ravel(),
                              (k[j][:, None] + frac * (k[j + 1] - k[j])[:, None]).ravel()])
        scan.add(np.tile(np.repeat(fi[j], frac.size), 2), new)


def _walk(n0: int, signs) -> list[int] | None:
    """Branch indices of the roots met walking up in kappa from the count ``n0`` at kappa = 0
    (each root changes the count by ``-sign(c_g)``); None unless it ends at zero."""
    n, out = n0, []
    for s in signs:
        j = n - 1 if s > 0 else n
        if j < 0:
            return None
        out.append(j)
        n -= int(s)
    return out if n == 0 else None


def _split_zgv_pairs(scan: _Scan, points) -> None:
    """Next to a ZGV point (frequency within :data:`ZGV_SPLIT`), a ZGV sample whose sign is
    that of both neighbours may still hide a pair of roots if the ZGV kappa lies outside it:
    the model locates the extremum of its function in exact arithmetic
    (:meth:`~dispersion.continuum.plate_model.PlateModel.split_pair`) and, where its sign is
    the other one, its kappa joins the samples (decided exactly)."""
    new_f, new_k = [], []
    for kz, wz in points:
        for i in np.flatnonzero(np.abs(scan.omega / wz - 1) <= ZGV_SPLIT):
            j = np.flatnonzero((scan.fi == i) & (scan.k == kz))
            if j.size == 0 or j[0] == 0 or j[0] + 1 >= scan.k.size:
                continue
            j = int(j[0])
            if not (np.sign(scan.g[j - 1]) == np.sign(scan.g[j]) == np.sign(scan.g[j + 1])):
                continue
            x = scan.model.split_pair(scan.kind, kz, float(scan.omega[i]), np.sign(scan.g[j]))
            if x is not None:
                new_f.append(i)
                new_k.append(x)
    if new_f:
        scan.add(np.array(new_f), np.array(new_k))
        scan.decide_exactly()


def _class_roots(model, kind, omega, step, rtol, max_depth, zgv_points):
    """Roots of one class of ``model`` at every Omega, labelled by the count."""
    failures = []
    k_hi, fails = _kappa_hi(model, kind, omega, model.kappa_start(omega))
    failures += fails
    scan = _Scan(model, kind, omega)
    counts = np.ceil(k_hi / step).astype(int) + 1
    fi = np.repeat(np.arange(omega.size), counts)
    start = np.concatenate([[0], np.cumsum(counts)[:-1]])
    k = (np.arange(fi.size) - start[fi]) * step
    k = np.minimum(k, k_hi[fi])
    extra_f, extra_k = [], []
    for kz, _ in zgv_points:
        sel = np.flatnonzero(kz < k_hi)
        extra_f.append(sel)
        extra_k.append(np.full(sel.size, kz))
    if extra_f:
        fi, k = np.concatenate([fi, *extra_f]), np.concatenate([k, *extra_k])
    scan.add(fi, k)
    _refine_dips(scan, max_depth)
    scan.decide_exactly()
    _split_zgv_pairs(scan, zgv_points)
    c = scan.certain()
    sfi, sk, sg = scan.fi[c], scan.k[c], scan.g[c]
    same = sfi[1:] == sfi[:-1]
    change = same & (np.sign(sg[1:]) != np.sign(sg[:-1]))
    # same sign with round-off-level samples between: two roots closer than floating point
    hidden = same & ~change & (np.diff(c) > 1)
    for jj in np.flatnonzero(hidden):
        failures.append((float(omega[sfi[jj]]), kind, "two roots closer than round-off near "
                         f"kappa={sk[jj]:.6g}"))
    j = np.flatnonzero(change)
    rf = sfi[j]

    def f(idx, x):
        return model.dispersion(kind, x, omega[rf[idx]])[0]

    roots, _, _, unconverged = illinois(f, sk[j], sk[j + 1], sg[j], sg[j + 1], rtol)
    for i in np.flatnonzero(unconverged):
        failures.append((float(omega[rf[i]]), kind, "root refinement did not converge"))
    roots = model.polish(kind, roots, omega[rf])
    cells = np.stack([sk[j], sk[j + 1]], axis=1)
    roots, redone, uncertain = model.certify(kind, roots, omega[rf], cells)
    for i in uncertain:
        failures.append((float(omega[rf[i]]), kind, f"root near kappa={roots[i]:.6g} not "
                         f"certified to {ROOT_RTOL:.0e} relative"))
    group = model.slope(kind, roots, omega[rf], redone)
    labels = [""] * roots.size
    branch = [None] * roots.size
    # to just above the top frequency: a cut-off that *is* it to rounding counts (at_cutoff)
    cut = model.cutoffs(kind, float(omega.max()) * (1 + 1e-14))
    for i in range(omega.size):
        mine = np.flatnonzero(rf == i)
        g = group[mine]
        if not np.all(np.isfinite(g) & (g != 0)):
            bad = roots[mine][~(np.isfinite(g) & (g != 0))][0]
            failures.append((float(omega[i]), kind, f"group velocity undefined at "
                             f"kappa={bad:.6g}"))
            walk = None
        else:
            # N(0+): the cut-offs below Omega; a branch whose cut-off *is* Omega (within
            # round-off) may start just below or above it, so both counts are tried and
            # the one whose walk adds up is kept (its root at kappa = 0 is not propagating)
            tol = 8 * np.spacing(omega[i])
            lo = int(np.count_nonzero(cut < omega[i] - tol))
            hi = int(np.count_nonzero(cut <= omega[i] + tol))
            walks = [w for w in (_walk(n0, np.sign(g)) for n0 in range(lo, hi + 1))
                     if w is not None]
            walk = walks[0] if len(walks) == 1 else None
        if walk is None:
            for r in mine:
                labels[r] = f"{kind}?"
            failures.append((float(omega[i]), kind, "root count does not add up to the "
                             "branches below Omega (a root may be missing)"))
            continue
        for r, j in zip(mine, walk):
            labels[r], branch[r] = model.label(kind, j), j
    # a branch whose cut-off is Omega to rounding: its root next to kappa = 0 is rounding
    # (kappa ~ sqrt(eps)), the mode is at its cut-off (not propagating): dropped, named
    keep = np.ones(roots.size, dtype=bool)
    at = []
    for r, (lab, j) in enumerate(zip(labels, branch)):
        if j is not None and j < cut.size and at_cutoff(float(omega[rf[r]]), cut[j]) \
                and cut[j] > 0 and roots[r] < 1e-6:
            keep[r] = False
            at.append((int(rf[r]), lab))
    for i in range(omega.size):   # at the cut-off with no root found next to it: named too
        for j, w in enumerate(cut):
            if w > 0 and at_cutoff(float(omega[i]), w) and (i, model.label(kind, j)) not in at:
                at.append((i, model.label(kind, j)))
    labels = [lab for lab, k in zip(labels, keep) if k]
    return rf[keep], labels, roots[keep], group[keep], failures, at


def zgv_points_below(nu: float, omega_top: float, per_unit: float = 40.0):
    """Zero-group-velocity points of the exact branches with :math:`\\Omega \\le` omega_top.

    :func:`dispersion.continuum.velocities.zgv_points` on ``per_unit`` kappa samples per unit of
    kappa up to omega_top (120 to 4000 samples): a ZGV point has :math:`c_p > c_T`, so
    :math:`\\kappa < \\Omega`.

    >>> [(p.label, round(p.kappa, 6), round(p.omega, 6)) for p in zgv_points_below(0.3, 3.0)]
    [('S1', 0.838288, 2.730307)]
    """
    from dispersion.continuum.velocities import zgv_points as zgv_on_grid

    count = int(min(max(per_unit * omega_top, 120), 4000))
    return zgv_on_grid(nu, omega_top, omega_top, count + 1)


def modes_at_frequency(nu: float, omega, *, kinds=("S", "A", "SH"), step: float = 0.02,
                       rtol: float = 1e-15, max_depth: int = 12, zgv: bool = True,
                       ) -> FrequencyRoots:
    """Every propagating mode with real :math:`\\kappa > 0` at each :math:`\\Omega` in ``omega``.

    Parameters
    ----------
    nu : float or fractions.Fraction
        Poisson's ratio in (-1, 0.5), exact: the roots are certified at its exact value (a
        float's binary value; a material's :attr:`~dispersion.materials.materials.Material.nu_exact`).
    omega : array_like
        Dimensionless frequencies :math:`\\Omega = \\omega h / c_T` in
        [:data:`FREQUENCY_OMEGA_MIN`, :data:`FREQUENCY_OMEGA_MAX`].
    kinds : tuple
        Any of ``"S"``, ``"A"`` (Lamb) and ``"SH"``.
    step, rtol, max_depth :
        Kappa sample spacing, root tolerance, dip refinement depth (see module docstring).
    zgv : bool
        Find the zero-group-velocity points (their kappa join the samples; they are listed).

    Returns
    -------
    FrequencyRoots
    """
    nu_q = _exact(check_nu(nu))
    nu = float(nu_q)
    model = IsotropicPlate(nu_q)
    omega = _check_omegas(omega)
    check_positive("step", step)
    check_positive("rtol", rtol)
    bad = [k for k in kinds if k not in model.classes()]
    if bad or not kinds:
        raise InputError(f"kinds must be a non-empty subset of S, A, SH; got {kinds!r}")
    samples = float(np.sum(model.kappa_start(omega))) / step * len(kinds)
    if samples > MAX_SCAN_SAMPLES:
        raise InputError(f"the frequencies ask for about {samples:.3g} kappa samples; they "
                         f"must be <= {MAX_SCAN_SAMPLES:.0e} (about a minute): fewer or lower "
                         f"frequencies, or a larger step")
    points = ()
    if zgv and any(k in ("S", "A") for k in kinds):
        points = tuple(zgv_points_below(nu, float(omega.max()) * 1.05 + 0.5))
    return modes_of(model, omega, kinds=kinds, step=step, rtol=rtol, max_depth=max_depth,
                    zgv_points=points)


def modes_of(model, omega, *, kinds, step: float = 0.02, rtol: float = 1e-15,
             max_depth: int = 12, zgv_points=()) -> FrequencyRoots:
    """Every propagating mode of the classes ``kinds`` of any plate ``model`` (a
    :class:`~dispersion.continuum.plate_model.PlateModel`) at each checked Omega of
    ``omega``: the calculator of :func:`modes_at_frequency`, asking the model for its
    function, cut-offs, certificates and slopes. ``zgv_points``: the model's zero-group-
    velocity points near the frequencies (objects with ``label``, ``kappa`` and ``omega``),
    whose kappa join the samples."""
    wmax = float(omega.max())
    rows, failures, at_cut = [], [], []
    for kind in kinds:
        if model.closed_form(kind):
            for i, w in enumerate(omega):
                for lab, k, g in model.closed_form_roots(kind, float(w)):
                    rows.append((i, lab, k, g, kind))
                at_cut += [(i, model.label(kind, j)) for j, wc in
                           enumerate(model.cutoffs(kind, float(w) * (1 + 1e-15)))
                           if wc > 0 and at_cutoff(float(w), wc)]
            continue
        zk = [(p.kappa, p.omega) for p in zgv_points if p.label.rstrip("0123456789") == kind]
        rf, labels, roots, group, fails, at = _class_roots(model, kind, omega, step, rtol,
                                                           max_depth, zk)
        failures += fails
        at_cut += at
        rows += [(i, lab, k, g, kind) for i, lab, k, g in
                 zip(rf.tolist(), labels, roots.tolist(), group.tolist())]
    order = {k: n for n, k in enumerate(model.classes())}

    def number(label):  # "S?" (an uncertified root) sorts after every numbered mode
        digits = label.lstrip("SAHLM")
        return int(digits) if digits.isdigit() else 10**9

    rows.sort(key=lambda r: (r[0], number(r[1]), order[r[4]], r[2]))
    cutoffs = {}
    for kind in kinds:
        cutoffs.update(dict(model.cutoff_table(kind, wmax)))
    return FrequencyRoots(
        nu=getattr(model, "nu", float("nan")), omega=omega,
        index=np.array([r[0] for r in rows], dtype=int),
        label=tuple(r[1] for r in rows),
        kappa=np.array([r[2] for r in rows], dtype=float),
        group=np.array([r[3] for r in rows], dtype=float),
        cutoffs=cutoffs, zgv=tuple(zgv_points), failures=tuple(dict.fromkeys(failures)),
        at_cutoff=tuple(sorted(set(at_cut))), nu_exact=getattr(model, "nu_q", None))
