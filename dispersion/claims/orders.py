"""Claims about orders of accuracy over a range of degrees: ``kind = "order_range"``.

A paper's headline is often "this rule keeps the order of the consistent mass for every
degree". One claim states it for a range of p::

    [[claim]]
    name = "approximate-dual lumping keeps the consistent order, p = 1..4"
    source = "Nguyen et al., CMAME 2023, abstract"
    kind = "order_range"
    model = "bar"               # or "bloch" with branch = "S0" / "A0"
    mass = "dual-lumped"
    p_from = 1                  # the range p_from..p (inclusive)
    p = 4
    same_order_as = "consistent"   # a registered rule (default consistent)

For each degree the leading error term of the rule and of ``same_order_as`` are derived
exactly (:mod:`dispersion.waves.leading_error`: the periodic bar, or S0 / A0 of the
square-element Bloch patch n = max(p + 1, 3), r = 2/(n - p), so ``n``, ``r`` and contact keys
are refused); the claim holds where the rule's power is never lower. ``expect = "differs"``
states that the rule loses the order somewhere in the range.
"""
from __future__ import annotations

from dispersion.claims.bar_model import BarModel
from dispersion.claims.claim import Claim

__all__ = ["KINDS", "KIND_FIELDS", "P_TOP", "prepare", "order_claim", "task", "run", "verdict"]

KINDS = ("order_range",)
KIND_FIELDS = {"order_range": ("p_from", "same_order_as")}
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


def order_claim(entry: dict, common: dict, fail) -> Claim:
    """An ``order_range`` claim (``common``: the fields every kind has, the model checked)."""
    from dispersion.mass_rules.mass_rule import RULES

    model = common["model"]
    p = model.p
    if p > P_TOP:
        fail("p", f"must be at most {P_TOP} for an order claim, got {p}")
    lo = entry.get("p_from", 1)
    if type(lo) is not int or not 1 <= lo <= p:
        fail("p_from", f"must be an integer in [1, p = {p}], got {lo!r}")
    ref = entry.get("same_order_as", "consistent")
    if not isinstance(ref, str) or ref not in RULES or RULES[ref].redistributes:
        fail("same_order_as", "must name a registered rule without a contact set, got "
                              f"{ref!r}")
    if not isinstance(model, BarModel):
        if common["branch"] not in ("S0", "A0"):
            fail("branch", f"must be S0 or A0, got {common['branch']!r}")
    mass = getattr(model, "mass_name", None) or getattr(model.mass, "name", model.mass)
    return Claim(**common, printed=(("p_from", lo), ("same_order_as", ref)),
                 written=f"{mass} keeps the order of {ref} for p = {lo}..{p}")


def task(claim) -> tuple:
    d = dict(claim.printed)
    bar = isinstance(claim.model, BarModel)
    mass = claim.model.mass
    return ("order_range", "bar" if bar else claim.branch, getattr(mass, "name", mass),
            d["p_from"], claim.model.p, d["same_order_as"])


def _power(model: str, rule, p: int):
    from dispersion.discretization.leading_error import bar_leading_term, plate_leading_terms

    order = 2 * p + 4
    if model == "bar":
        return bar_leading_term(rule, p, order)
    return plate_leading_terms(rule, p, order)[f"plate {model}"]


def run(t: tuple):
    """``[(p, power of the rule, power of the reference), ...]`` (None: beyond the series)."""
    _, model, mass, lo, hi, ref = t
    return [(p, _power(model, mass, p)[0], _power(model, ref, p)[0])
            for p in range(lo, hi + 1)]


def verdict(claim, derived) -> tuple[bool, str, str, str]:
    """``(holds, printed, derived, difference)`` as text."""
    var = "theta" if isinstance(claim.model, BarModel) else "kappa"

    def show(k):
        return "beyond the series" if k is None else f"{var}^{k}"

    lower = [(p, k, kr) for p, k, kr in derived if k is not None and (kr is None or k < kr)]
    shown = "; ".join(f"p={p}: {show(k)} (reference {show(kr)})" for p, k, kr in derived)
    diff = "; ".join(f"p={p}: leading error {show(k)}, lower than {show(kr)}"
                     for p, k, kr in lower)
    return not lower, claim.written, shown, diff
