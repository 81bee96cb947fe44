"""Work a request may ask for: stated cost rules, checked before the work starts.

Every entry point whose cost grows without bound in one of its arguments checks that
argument here first, so the API, the claims files and the command line refuse the same
requests, at once, with an :class:`~dispersion.errors.InputError` naming the bound. The
budget of one request is about a minute of CPU and a gibibyte of memory on the 2-core
development machine; each bound is the largest size whose measured (fitted) cost stays
inside it. The measurements are ``benchmarks/bench_request_costs.py`` (CPU seconds, the
machine shared with other jobs: the lead re-times them on a quiet machine).

1. **Exact maximum of the periodic bar** (:func:`dispersion.time_stepping.timestep.bar_omega_max`,
   ``critical_step(model="bar")``, claims of kind ``critical_step`` on the bar, ``dispersion
   timestep --model bar``): a rational function of :math:`\\cos\\theta` of degree about p is
   maximised exactly (its critical points are algebraic numbers). Measured CPU of one call
   (the rule and the consistent reference), at p = 10, 12, 14: dual-lumped 7.5, 44 s and
   more than 150 s (p = 13: more than 170 s); nodal-greville 4.1, 8.3, 29 s (63 s at 15);
   interpolatory-nodal 4.1, 7.8, 28 s; lumped 2.5, 4.7, 18 s; HRZ 2.3, 4.4, 15 s (65 s at
   16); sms 3.5, 6.1, 16 s; dual-gram and dual-consistent 2.5 to 8.8 s; consistent and
   nodal-lobatto under 4 s up to p = 16. The cost grows several-fold per degree at the top.
   Bound: :data:`BAR_P_MAX` = 12, the largest p at which every registered rule of the bar
   finished within the minute (the dearest, dual-lumped, at 44 s).
2. **Fully discrete series** (:func:`dispersion.time_stepping.fully_discrete.fully_discrete_series`,
   :func:`~dispersion.time_stepping.fully_discrete.time_series`, claims of kind
   ``fully_discrete_series``). (a) The time series to m terms (:math:`m` = order // lowest
   power) is a sympy series of degree m. Measured for ``{2: 1}``: m = 64, 128, 256 take
   0.8, 1.7, 12.6 s (growth about m^3); m = 512 timed out at 120 s. Bound:
   :data:`TIME_TERMS_MAX` = 128 terms. (b) The semi-discrete series :math:`S` (k nonzero
   terms up to the order) is raised to the powers 1..m and expanded in full: :math:`W =
   \\sum_{j=1}^{m} \\binom{j + k - 1}{k - 1}` products of coefficients (:func:`series_work`).
   Measured on the S0 and A0 series of the default patch: with a number for nu, W = 923,
   12375, 184755 take 0.28, 2.4, 36 s (about 2e-4 s a product); with nu a symbol (its
   coefficients rational functions), W = 9, 19, 55, 69 take 0.12, 0.37, 3.1, 8.4 s and
   W = 126 more than 200 s. Bounds: W at most :data:`SERIES_WORK_MAX` = 200000 with numbers,
   :data:`SYMBOLIC_SERIES_WORK_MAX` = 70 with symbols. (A truncated product, S^j from
   S^(j-1) S to the order, would cost far less; the bound is for the code as it is.)
3. **Fully discrete series of the bar in claims** (kind ``fully_discrete_series``, model
   ``bar``): the semi-discrete series is a sympy series of :math:`\\omega^2(\\cos\\kappa)` to
   the claim's highest power of kappa. Measured (HRZ): order 12, 16, 20 take 0.3, 2.3,
   37 s at p = 1 and order 16 about 3 to 4 s for p = 2 to 8 (order 20 timed out at 90 s
   from p = 2). Bound: order (highest power of kappa) :data:`BAR_SERIES_ORDER_MAX` = 16,
   and p at most :data:`BAR_P_MAX`.
4. **Phases of the critical-step grid** (:func:`dispersion.time_stepping.timestep.patch_omega_max`,
   ``critical_time_step``, ``critical_step``): every phase holds its stiffness and mass
   matrices and their eigenvalues, of size 2n; measured 115 KiB a phase at 2n = 48 (10^4
   phases: 1.3 GiB, 8.9 s) and 1.4 KiB at 2n = 6, about 50 bytes per phase and squared
   size. Bound: phases x (2n)^2 at most :data:`PHASE_WORK_MAX` = 2e7 (about 1 GiB).
5. **Worker processes** (:func:`dispersion.sweep.parallel_map`,
   :func:`dispersion.sweep.process_pool`): at most :data:`dispersion.defaults.MAX_JOBS_PER_CPU`
   per usable CPU (each holds its own copy of the toolkit, about 150 MB).
6. **Discrete branches** (:func:`dispersion.answers.branch_table.branch_table`,
   :meth:`dispersion.patch_model.PatchModel.branches`, ``dispersion branches``), two costs:

   (a) *per kappa*: every kappa solves the pencil of each rule, of size 2n. Measured, 400
   kappa, consistent + singular: n = 10 in 3.4 s, n = 20 in 48 s, n = 30 in 180 s (like n^3).
   Bound: count x (mass rules) x n^3 at most :data:`DISCRETE_WORK_MAX` (the default run of
   two rules and 400 kappa at n = 24 in about a minute).

   (b) *once per rule*: the exact patch of the rule and, where the mirror blocks have at most
   12 rows (n <= 12), its exact characteristic polynomial (``bench_request_costs.py --only
   discrete``: CPU of ``branch_table`` with two kappa). Every rule but one stays within the
   minute up to p = 24: at n = p + 1, p = 24, consistent 25 s, lumped 25 s, singular 32 s,
   nodal-lobatto 32 s; at n = 12, p = 10, consistent 12 s. The approximate-dual rule
   ``dual-lumped`` does not: its exact patch took 6.5, 12.5 and 39 s at p = 12, 14, 16
   (n = p + 1; 38 s at p = 12, n = 23; 15 s at p = 4, n = 30) and more than 15 minutes at
   p = 24; its polynomial at n = 12 took 2.5, 7.4,
   17, 40 and 95 s at p = 2, 4, 6, 8, 10. Bounds: :data:`DISCRETE_P_MAX`, per rule and
   part, the largest p measured within the minute (a user's rule, a redistribution of weights
   or a callable, is bounded as the registered rules other than ``dual-lumped``).

   (c) *n with p*: the exact patch grows faster than n^2, and faster at higher p (CPU,
   consistent and singular: p = 2 at n = 25: 6.6 and 9.5 s, at n = 35: 12.4 and 21 s, at
   n = 50: 32 s (consistent); p = 12 at n = 13: 3.1 s, at n = 23: 32 and 35 s, at n = 35: 77
   s (consistent); n = p + 1 at p = 12, 16, 20, 24: 3.1, 7.3, 13, 25 s (consistent); p = 24,
   n = 27: 74 s). Singular at p = 2, n = 40 met the extended-precision solver's own bound
   (70 s a kappa). Bound: n at most :func:`discrete_n_max` (p) = max(p + 1, 35 - 1.3 (p - 2)):
   35 at p = 2 (the two default rules 33 s), 22 at p = 12 (about 57 s, from n = 23's 66 s),
   p + 1 from p = 16 (p = 24: 57 s), linear between the measured corners; so every n the
   command accepts for its p runs at its smallest grid (count = 2) with its default rules.

7. **Evanescent modes** (:func:`dispersion.continuum.layered.evanescent_modes.evanescent_modes`,
   ``dispersion branches --exact --evanescent``): per frequency and mode class, the
   argument of the exact function is followed around a rectangle of half-width R and height
   2 Im kappa_max, one ball evaluation through the whole sublayer chain per sample. Work:
   :math:`W = \\sum 8 (R + \\kappa''_{max}) / 0.25 \\times (\\text{sublayers} + 10)` over
   frequencies and classes, R estimated before the work as 1.25 Omega s_max + 1 (s_max the
   slowest bulk wave's slowness in the units of the plate). Measured (wall, one frequency,
   every class, 60 dB per thickness, the machine shared): 1 mm steel at Omega 1, 10, 30:
   1.9, 7.0, 11.4 s for W = 9.5e3, 3.7e4, 1.6e5 (the estimate is conservative at small
   Omega, where SAFE and the propagating count dominate). Bound:
   :data:`EVANESCENT_WORK_MAX` = 1e6 (six frequencies at Omega 30: about a minute).

>>> check_bar_degree(24)
Traceback (most recent call last):
...
dispersion.errors.InputError: p = 24 is beyond the exact maximum of the periodic bar: at most p = 12 (the dearest rule takes most of a minute at p = 12, and several times longer with each degree)
"""
from __future__ import annotations

import numbers

from dispersion import defaults
from dispersion.errors import InputError

__all__ = ["BAR_P_MAX", "TIME_TERMS_MAX", "SERIES_WORK_MAX", "SYMBOLIC_SERIES_WORK_MAX",
           "BAR_SERIES_ORDER_MAX", "PHASE_WORK_MAX", "DISCRETE_WORK_MAX", "DISCRETE_P_MAX",
           "DISCRETE_N_MAX", "POLYNOMIAL_N_MAX", "discrete_n_max", "check_bar_degree", "check_time_terms",
           "series_work", "check_series_work", "check_bar_series", "check_phases",
           "check_discrete_branches", "check_jobs", "max_jobs", "check_claim",
           "EVANESCENT_WORK_MAX", "check_evanescent_work"]

#: Most work W of one request for evanescent modes (rule 7).
EVANESCENT_WORK_MAX = 1_000_000


def check_evanescent_work(work: float, frequencies: int) -> None:
    """Rule 7: the estimated work of an evanescent-mode request.

    >>> check_evanescent_work(2e6, 10)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: evanescent modes at 10 frequencies: estimated work 2e+06 is more than the limit of 1e+06 (about a minute: ball arithmetic along each class's rectangle): ask for fewer frequencies (at most 5 of these), a lower --decay-max or a lower frequency
    """
    if work > EVANESCENT_WORK_MAX:
        fits = max(1, int(frequencies * EVANESCENT_WORK_MAX // work))
        raise InputError(f"evanescent modes at {frequencies} frequencies: estimated work "
                         f"{work:.3g} is more than the limit of {EVANESCENT_WORK_MAX:.0e} "
                         "(about a minute: ball arithmetic along each class's rectangle): ask "
                         f"for fewer frequencies (at most {fits} of these), a lower "
                         "--decay-max or a lower frequency")


#: Highest degree of the exact maximum of the periodic bar (rule 1).
BAR_P_MAX = 12
#: Most terms of the time series of a fully discrete series (rule 2).
TIME_TERMS_MAX = 128
#: Most products of coefficients expanding the powers of a semi-discrete series (rule 2b),
#: with numbers and with symbols in its coefficients.
SERIES_WORK_MAX = 200_000
SYMBOLIC_SERIES_WORK_MAX = 70
#: Highest power of kappa of a fully discrete series claim on the bar (rule 3).
BAR_SERIES_ORDER_MAX = 16
#: Most phases x (2n)^2 of the critical-step grid (rule 4).
PHASE_WORK_MAX = 20_000_000
#: Most count x (mass rules) x n^3 of discrete branches (rule 6a).
DISCRETE_WORK_MAX = 2 * 400 * 24**3
#: Largest n of discrete branches at any p (rule 6c): :func:`discrete_n_max` at p = 1.
DISCRETE_N_MAX = 36
#: Largest n whose mirror blocks (n rows each) take the exact characteristic polynomial
#: (:data:`dispersion.discretization.pencil_polynomial.MAX_BLOCK`): the setup of 6b's
#: "polynomial" part.
POLYNOMIAL_N_MAX = 12
#: Largest p of discrete branches per rule and part of its setup (rule 6b): ``"patch"`` (its
#: exact patch, any n) and ``"polynomial"`` (its characteristic polynomial, n <= 12). A rule
#: not named here is within the minute up to :data:`dispersion.defaults.P_MAX`.
DISCRETE_P_MAX = {"dual-lumped": {"patch": 16, "polynomial": 8}}


def _integer(name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise InputError(f"{name} must be an integer, got {value!r}")
    return int(value)


def check_bar_degree(p) -> int:
    """Rule 1: the degree of an exact maximum of the periodic bar."""
    p = _integer("p", p)
    if p > BAR_P_MAX:
        raise InputError(f"p = {p} is beyond the exact maximum of the periodic bar: at most "
                         f"p = {BAR_P_MAX} (the dearest rule takes most of a minute at "
                         f"p = {BAR_P_MAX}, and several times longer with each degree)")
    return p


def check_time_terms(terms, what: str = "order") -> int:
    """Rule 2: terms of the time series of a fully discrete series.

    >>> check_time_terms(10**6 // 2, "order // lowest power")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: order // lowest power = 500000 terms of the time series, more than the limit of 128 (its cost grows as the cube)
    """
    terms = _integer(what, terms)
    if terms > TIME_TERMS_MAX:
        raise InputError(f"{what} = {terms} terms of the time series, more than the limit of "
                         f"{TIME_TERMS_MAX} (its cost grows as the cube)")
    return terms


def series_work(k: int, m: int) -> int:
    """Rule 2b: the terms of the full expansions of :math:`S^1, \\dots, S^m`, S a sum of k
    terms (capped just above the larger bound).

    >>> series_work(8, 8), series_work(4, 4)
    (12869, 69)
    """
    from math import comb

    total = 0
    for j in range(1, m + 1):
        total += comb(j + k - 1, k - 1)
        if total > SERIES_WORK_MAX:
            return SERIES_WORK_MAX + 1
    return total


def check_series_work(k: int, m: int, symbolic: bool) -> None:
    """Rule 2b for a series of k nonzero terms raised to the powers 1..m."""
    limit = SYMBOLIC_SERIES_WORK_MAX if symbolic else SERIES_WORK_MAX
    work = series_work(k, m)
    if work > limit:
        count = f"more than {SERIES_WORK_MAX}" if work > SERIES_WORK_MAX else str(work)
        kind = "symbolic" if symbolic else "numeric"
        raise InputError(f"the fully discrete series would expand {k} terms to the powers "
                         f"1..{m}: {count} products of {kind} coefficients, more than the "
                         f"limit of {limit} (lower the order"
                         + (", or give nu a value)" if symbolic else ")"))


def check_bar_series(p, order) -> None:
    """Rule 3: a fully discrete series of the bar to kappa^order at degree p."""
    check_bar_degree(p)
    order = _integer("order", order)
    if order > BAR_SERIES_ORDER_MAX:
        raise InputError(f"kappa^{order} is beyond the series of the periodic bar: at most "
                         f"kappa^{BAR_SERIES_ORDER_MAX} (kappa^20 takes over a minute)")


def check_phases(n_theta, size: int) -> int:
    """Rule 4: ``n_theta`` phases of matrices of size ``size`` (2n).

    >>> check_phases(10**9, 6)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: n_theta = 1000000000 phases of 6 x 6 matrices is more than the limit of n_theta x size^2 <= 20000000 (about 1 GiB): at most n_theta = 555555
    """
    n_theta = _integer("n_theta", n_theta)
    if n_theta * size * size > PHASE_WORK_MAX:
        raise InputError(f"n_theta = {n_theta} phases of {size} x {size} matrices is more than "
                         f"the limit of n_theta x size^2 <= {PHASE_WORK_MAX} (about 1 GiB): at "
                         f"most n_theta = {PHASE_WORK_MAX // (size * size)}")
    return n_theta


def discrete_n_max(p: int) -> int:
    """Rule 6c: the largest n of discrete branches at degree ``p``.

    >>> [discrete_n_max(p) for p in (1, 2, 12, 16, 24)]
    [36, 35, 22, 17, 25]
    """
    return max(int(p) + 1, 35 - int(1.3 * (int(p) - 2)))


def check_discrete_branches(count, rules, p, n) -> int:
    """Rule 6: discrete branches of ``rules`` (names or rules) at degree ``p``, ``n`` control
    points, on ``count`` kappa; returns count x (rules) x n^3. Every refusal names values the
    command accepts: a count of at least 2, an n of at least p + 1.

    >>> check_discrete_branches(2, ["dual-lumped"], 24, 25)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: mass rule 'dual-lumped' at p = 24 is beyond the work bound of discrete branches: its exact patch at most p = 16 (the dearest p measured within a minute; it grows several-fold with each two degrees)
    >>> check_discrete_branches(2, ["consistent", "singular"], 2, 200)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: n = 200 at p = 2 is beyond the work bound of discrete branches: at most n = 35 at this p (the exact patches of two rules in about a minute)
    """
    count, p, n = _integer("count", count), _integer("p", p), _integer("n", n)
    names = [getattr(r, "name", r) for r in rules]
    for name in names:
        bounds = DISCRETE_P_MAX.get(name, {})  # a user rule cannot take a registered name
        if p > bounds.get("patch", defaults.P_MAX):
            raise InputError(f"mass rule {name!r} at p = {p} is beyond the work bound of "
                             f"discrete branches: its exact patch at most p = "
                             f"{bounds['patch']} (the dearest p measured within a minute; it "
                             "grows several-fold with each two degrees)")
        if n <= POLYNOMIAL_N_MAX and p > bounds.get("polynomial", defaults.P_MAX):
            raise InputError(f"mass rule {name!r} at p = {p} with n = {n} is beyond the work "
                             f"bound of discrete branches: its exact characteristic "
                             f"polynomial (n <= {POLYNOMIAL_N_MAX}) at most p = "
                             f"{bounds['polynomial']}; with n >= {POLYNOMIAL_N_MAX + 1} it "
                             "takes the float eigen-solver instead")
    if n > discrete_n_max(p):
        raise InputError(f"n = {n} at p = {p} is beyond the work bound of discrete branches: "
                         f"at most n = {discrete_n_max(p)} at this p (the exact patches of two "
                         "rules in about a minute)")
    work = count * len(names) * n**3
    if work > DISCRETE_WORK_MAX:
        most = DISCRETE_WORK_MAX // (len(names) * n**3)
        if most >= 2:
            advice = f"at most count = {most} at n = {n} with {len(names)} mass rule(s)"
        else:  # no grid fits: the n that does, with these rules and with one
            n_fit = int((DISCRETE_WORK_MAX // (2 * len(names))) ** (1 / 3) + 1e-9)
            advice = (f"no grid of 2 kappa or more fits at n = {n} with {len(names)} mass "
                      f"rule(s): at most n = {n_fit}")
        raise InputError(f"count * (mass rules) * n^3 must be <= {DISCRETE_WORK_MAX} (about a "
                         f"minute), got {work}: {advice}")
    return work


def max_jobs() -> int:
    """Rule 5: the most worker processes, :data:`~dispersion.defaults.MAX_JOBS_PER_CPU` per
    usable CPU."""
    import os

    try:
        cpus = len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not on Linux
        cpus = os.cpu_count() or 1
    return defaults.MAX_JOBS_PER_CPU * max(1, cpus)


def check_jobs(jobs, name: str = "jobs") -> int:
    """Rule 5: a worker count in [1, :func:`max_jobs`]."""
    if isinstance(jobs, bool) or not isinstance(jobs, numbers.Integral) \
            or not 1 <= jobs <= max_jobs():
        raise InputError(f"{name} must be an integer in [1, {max_jobs()}] "
                         f"({defaults.MAX_JOBS_PER_CPU} per usable CPU), got {jobs!r}")
    return int(jobs)


def _claim_order(claim) -> int:
    return max((i for (i, _), _ in claim.printed[1:]), default=0)


def check_claim(claim) -> None:
    """Rules 1, 2b and 3 for a claim of :mod:`dispersion.claims` (other kinds are bounded by
    the series engine's own limits and :data:`dispersion.claims.orders.P_TOP`)."""
    model = claim.model
    if getattr(model, "name", None) != "bar":
        if claim.kind == "fully_discrete_series":  # a plate's S0 (kappa^2, 4, ...) or A0 (4, ...)
            order = _claim_order(claim)
            lowest = 2 if claim.branch == "S0" else 4
            check_series_work(max(0, (order - lowest) // 2 + 1), order // lowest,
                              claim.nu is None)
        return
    if claim.kind == "critical_step":
        check_bar_degree(model.p)
    elif claim.kind == "fully_discrete_series":
        check_bar_series(model.p, _claim_order(claim))
