"""Claims about the leading error term: ``kind = "order_range"`` and ``kind = "leading_term"``.

The *leading error term* of a rule at degree p is :math:`c\\,x^k`, the first term in which
its dispersion relation departs from the exact one, derived exactly
(:mod:`dispersion.discretization.leading_error`): on the periodic bar
:math:`\\omega_h^2/\\omega^2 - 1 = c\\,\\theta^k + O(\\theta^{k+2})` with c rational; on S0 / A0
of the square-element Bloch patch (n = max(p + 1, 3), r = 2/(n - p); so ``n``, ``r`` and
contact keys are refused) the first power of kappa at which the power-balance series of
:math:`\\Omega^2` differs from the exact Rayleigh-Lamb series, c exact in nu. Series go to
:math:`x^{2p+4}`; a rule that agrees that far has no leading term ("beyond").

A paper's headline "this rule keeps the accuracy of the consistent mass for every degree"
is one ``order_range`` claim over a range of p, with exactly one of two comparisons::

    [[claim]]
    name = "approximate-dual lumping has the consistent leading term, p = 1..4"
    kind = "order_range"
    model = "bar"               # or "bloch" with branch = "S0" / "A0"
    mass = "dual-lumped"
    p_from = 1                  # the range p_from..p (inclusive)
    p = 4
    same_leading_term_as = "consistent"   # order AND coefficient equal, every p

``same_leading_term_as = R``
    exact: at every p of the range the rule's leading term equals R's, power and coefficient
    (the difference cancels to zero; in nu on the plate). This tells apart rules of one order:
    at p = 2 the approximate duals of reproduction degree q = 1 and q = p both err at
    theta^4, with -19/360 against 1/720.
``at_least_order_of = R``
    a bound: the rule's power is never below R's (what the old key ``same_order_as`` meant,
    despite its name). Every rule is "at least" as accurate as a weaker one, so this holds
    by default against the lumped mass; state it against the rule whose order is the claim.

``same_order_as`` is the deprecated name of ``at_least_order_of``: still read, with the same
meaning, and the claim's text says so (the files of ``examples/literature`` use the new keys).
``expect = "differs"`` states that the comparison fails somewhere in the range.

A ``leading_term`` claim states the term itself, at one degree, as a paper prints it::

    [[claim]]
    name = "q = 1 at p = 2: -19/360 theta^4"
    kind = "leading_term"
    model = "bar"               # or "bloch" with branch = "S0" / "A0"
    mass = "dual-lumped-q1"     # a registered rule or a family member's name
    p = 2
    power = 4                   # even, 0 .. 2p + 4
    coefficient = "-19/360"     # exact: a number, or an expression in nu (plate)

It holds when the derived power equals ``power`` and the coefficient cancels exactly.
"""
from __future__ import annotations

import functools

import sympy

from dispersion.claims.bar_model import BarModel
from dispersion.claims.claim import Claim
from dispersion.claims.claim_fields import expression, shown

__all__ = ["KINDS", "KIND_FIELDS", "COMPARISONS", "DEPRECATED", "P_TOP", "prepare",
           "order_claim", "leading_claim", "leading_term", "task", "run", "verdict"]

KINDS = ("order_range", "leading_term")
#: The comparisons of an order claim (exactly one is given; the default is the bound against
#: the consistent mass, for files written before the exact comparison existed).
COMPARISONS = ("same_leading_term_as", "at_least_order_of")
#: Old key -> new key, read with the new key's meaning.
DEPRECATED = {"same_order_as": "at_least_order_of"}
KIND_FIELDS = {"order_range": ("p_from", *COMPARISONS, *DEPRECATED),
               "leading_term": ("power", "coefficient", "syntax")}
#: Highest degree of an order claim (the exact plate series to kappa^(2p+4) stays ~1 s).
P_TOP = 6


def prepare(entry: dict, fail) -> dict:
    """``entry`` with the square-element patch of its top degree (``model = "bloch"``):
    n = max(p + 1, 3), r = 2/(n - p); n, r and contact keys given in the file are refused."""
    if entry.get("model") != "bloch":
        return entry
    for key in ("n", "r", "contact", "gamma_s", "weights"):
        if key in entry:
            fail(key, "an order claim uses the square-element patch of each degree "
                      "(n = max(p + 1, 3), r = 2/(n - p)); remove this key")
    p = entry.get("p")
    if type(p) is not int or not 1 <= p <= P_TOP:
        fail("p", f"must be an integer in [1, {P_TOP}] for an order claim, got {p!r}")
    n = max(p + 1, 3)
    return {**entry, "n": n, "r": f"2/{n - p}"}


def _check_model(common: dict, fail) -> int:
    model = common["model"]
    if model.p > P_TOP:
        fail("p", f"must be at most {P_TOP} for an order claim, got {model.p}")
    if not isinstance(model, BarModel) and common["branch"] not in ("S0", "A0"):
        fail("branch", f"must be S0 or A0, got {common['branch']!r}")
    return model.p


def _mass_name(model) -> str:
    return getattr(model, "mass_name", None) or getattr(model.mass, "name", model.mass)


def order_claim(entry: dict, common: dict, fail) -> Claim:
    """An ``order_range`` claim (``common``: the fields every kind has, the model checked)."""
    from dispersion.mass_rules.mass_rule import get_rule
    from dispersion.errors import InputError

    p = _check_model(common, fail)
    lo = entry.get("p_from", 1)
    if type(lo) is not int or not 1 <= lo <= p:
        fail("p_from", f"must be an integer in [1, p = {p}], got {lo!r}")
    given = [k for k in (*COMPARISONS, *DEPRECATED) if k in entry]
    if len(given) > 1:
        fail(given[1], f"give one comparison of {', '.join(COMPARISONS)}, got "
                       f"{' and '.join(given)}")
    key = given[0] if given else "at_least_order_of"
    ref = entry.get(key, "consistent")
    try:
        rule = get_rule(ref) if isinstance(ref, str) else None
    except InputError:
        rule = None
    if rule is None or rule.redistributes:
        fail(key, f"must name a registered rule without a contact set, got {shown(ref)}")
    comparison = DEPRECATED.get(key, key)
    mass = _mass_name(common["model"])
    if comparison == "same_leading_term_as":
        written = f"{mass} has the leading error term of {ref} for p = {lo}..{p}"
    else:
        written = f"{mass} keeps at least the order of {ref} for p = {lo}..{p}"
    if key in DEPRECATED:
        written += f" (key {key!r}: deprecated name of {comparison!r})"
    return Claim(**common, printed=(("p_from", lo), (comparison, ref)), written=written)


def leading_claim(entry: dict, common: dict, fail) -> Claim:
    """A ``leading_term`` claim: ``power`` and ``coefficient`` at the claim's degree p."""
    from dispersion.claims import reader
    from dispersion.symbolic.power_balance import NU

    p = _check_model(common, fail)
    k = entry.get("power")
    if type(k) is not int or k < 0 or k % 2 or k > 2 * p + 4:
        fail("power", f"must be an even integer in [0, 2p + 4 = {2 * p + 4}], got {shown(k)}")
    if "coefficient" not in entry:
        fail("coefficient", "required: the leading coefficient (a number, or an expression "
                            "in nu on the plate)")
    syntax = entry.get("syntax", "sympy")
    if syntax not in reader.SYNTAXES:
        fail("syntax", f"must be 'sympy' or 'latex', got {shown(syntax)}")
    c = expression(entry["coefficient"], "coefficient", syntax, fail)
    allowed = set() if isinstance(common["model"], BarModel) else {NU}
    extra = c.free_symbols - allowed
    if extra:
        fail("coefficient", f"symbol {sorted(map(str, extra))[0]!r} is not a parameter of "
                            "this model" + (" (the bar's coefficient is a number)"
                                            if not allowed else ""))
    if c == 0:
        fail("coefficient", "a leading term has a coefficient other than 0")
    var = "theta" if isinstance(common["model"], BarModel) else "kappa"
    return Claim(**common, printed=(("power", k), ("coefficient", c)),
                 written=f"leading error term ({c})*{var}^{k} at p = {p}")


def _branch(claim) -> str:
    return "bar" if isinstance(claim.model, BarModel) else claim.branch


def task(claim) -> tuple:
    """The derivation a claim needs, hashable (mass by name: picklable, shared)."""
    mass = _mass_name(claim.model)
    if claim.kind == "leading_term":
        return ("leading_term", _branch(claim), mass, claim.model.p)
    d = dict(claim.printed)
    comparison = next(k for k in COMPARISONS if k in d)
    return ("order_range", _branch(claim), mass, d["p_from"], claim.model.p, d[comparison])


@functools.lru_cache(maxsize=256)
def leading_term(model: str, mass: str, p: int) -> tuple:
    """``(k, c)`` of rule ``mass`` at degree ``p``: ``model`` is ``"bar"``, ``"S0"`` or
    ``"A0"``; c a sympy number (bar) or expression in nu (plate); ``(None, None)``: beyond
    the series to :math:`x^{2p+4}`. Cached per process: S0 and A0 share one derivation."""
    from dispersion.discretization.leading_error import bar_leading_exact

    if model == "bar":
        k, c = bar_leading_exact(mass, p, 2 * p + 4)
        return k, None if c is None else sympy.Rational(c.numerator, c.denominator)
    return _plate(mass, p)[f"plate {model}"]


@functools.lru_cache(maxsize=64)
def _plate(mass: str, p: int) -> dict:
    from dispersion.discretization.leading_error import plate_leading_exact

    return plate_leading_exact(mass, p, 2 * p + 4)


def run(t: tuple):
    """``leading_term``: ``(k, c)``; ``order_range``: ``[(p, (k, c), (k_ref, c_ref)), ...]``."""
    if t[0] == "leading_term":
        _, model, mass, p = t
        return leading_term(model, mass, p)
    _, model, mass, lo, hi, ref = t
    return [(p, leading_term(model, mass, p), leading_term(model, ref, p))
            for p in range(lo, hi + 1)]


def _same(a: tuple, b: tuple) -> bool:
    """Equal leading terms: the same power and a difference that cancels to zero."""
    if a[0] != b[0]:
        return False
    return a[1] is None and b[1] is None or (
        a[1] is not None and b[1] is not None and sympy.cancel(a[1] - b[1]) == 0)


def verdict(claim, derived) -> tuple[bool, str, str, str]:
    """``(holds, printed, derived, difference)`` as text."""
    var = "theta" if isinstance(claim.model, BarModel) else "kappa"

    def show(term):
        k, c = term
        return "beyond the series" if k is None else f"({c})*{var}^{k}"

    if claim.kind == "leading_term":
        d = dict(claim.printed)
        holds = _same((d["power"], d["coefficient"]), derived)
        diff = "" if holds else (
            f"power {var}^{derived[0]}, claimed {var}^{d['power']}" if derived[0] != d["power"]
            else _coefficient_difference(d["coefficient"], derived[1]))
        return holds, claim.written, show(derived), diff
    d = dict(claim.printed)
    if "same_leading_term_as" in d:
        bad = [(p, t, tr) for p, t, tr in derived if not _same(t, tr)]
        what = "leading term"
    else:
        bad = [(p, t, tr) for p, t, tr in derived
               if t[0] is not None and (tr[0] is None or t[0] < tr[0])]
        what = "leading error order"
    shown_ = "; ".join(f"p={p}: {show(t)} (reference {show(tr)})" for p, t, tr in derived)
    diff = "; ".join(f"p={p}: {what} {show(t)}, the reference's {show(tr)}"
                     for p, t, tr in bad)
    return not bad, claim.written, shown_, diff


def _coefficient_difference(printed, derived) -> str:
    ratio = sympy.cancel(printed / derived)
    if ratio.is_number:
        return f"coefficient: printed = {ratio} * derived"
    return f"coefficient: printed {printed}, derived {derived}"
