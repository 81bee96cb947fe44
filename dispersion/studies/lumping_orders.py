"""Exact orders of accuracy of every mass rule: which rules keep the order of the consistent mass.

For each rule and degree p, the *leading error term* of

* the periodic bar (uniform B-splines, element length h, :math:`\\theta = kh`):
  :math:`\\omega_h^2 / \\omega^2 - 1 = c\\, \\theta^{k} + O(\\theta^{k+2})`, from the exact
  rational function :func:`dispersion.time_stepping.timestep.bar_omega_squared` expanded at
  :math:`\\theta = 0` (c a rational number);
* S0 and A0 of the Bloch plate patch (plane strain, n = max(p + 1, 3) control points through
  the thickness, r = b/H = 2/(n - p), the cost-accuracy patch): the lowest power
  :math:`\\kappa^k` at which the power-balance series of :math:`\\Omega^2`
  (:func:`dispersion.symbolic.power_balance.discrete_series`) differs from the exact
  Rayleigh-Lamb series (:func:`dispersion.continuum.exact_series.exact_series`), and the
  difference of the coefficients there, exact in nu.

A rule *keeps the order* of the consistent mass where its k is at least the consistent
mass's k at the same p (bar; plate S0 and A0). Series are derived to :math:`\\kappa^{2p+4}`,
beyond the consistent mass's leading term for every p here; a rule that agrees with the exact
series that far is reported with ``power = None`` ("beyond").

>>> res = lumping_orders(degrees=(1,), rules=("consistent", "lumped"), plate=False)
>>> [(r.rule, r.power, r.coefficient) for r in res.terms]     # theta^2/12 and -theta^2/12
[('consistent', 2, '1/12'), ('lumped', 2, '-1/12')]
"""
from __future__ import annotations

import time
from dataclasses import asdict, dataclass

from dispersion.discretization.leading_error import bar_leading_term, plate_leading_terms

__all__ = ["OrderRow", "LumpingOrders", "lumping_orders", "measure", "RULES"]

#: The rules of the table: every registered rule (the singular ones on the plate only, they
#: need a contact set) and the approximate dual of reproduction degree 1 (the family's
#: parameter; q = 0 is the row-sum lumped mass, q = p the registered ``dual-lumped``).
RULES = None  # the registry's names, read at call time (never copied)


@dataclass(frozen=True)
class OrderRow:
    """One rule, degree and model: the leading error term :math:`c\\,x^{k}`."""

    rule: str
    p: int
    model: str          # "bar", "plate S0", "plate A0"
    power: int | None   # k (None: no difference up to the derived order)
    coefficient: str    # c, exact (in nu on the plate); "" where power is None
    consistent_power: int | None
    keeps_order: bool


@dataclass(frozen=True)
class LumpingOrders:
    """The table and its inputs."""

    degrees: tuple[int, ...]
    rules: tuple[str, ...]
    plate_r: str
    plate_n: str
    series_order: str
    terms: tuple[OrderRow, ...]
    seconds: float
    failures: tuple[str, ...] = ()
    #: ``(name, description, explicit cost in words)`` per rule, from the registry.
    rule_info: tuple[tuple[str, str, str], ...] = ()
    #: The literature's claims files verified: ``(file, claim, source, status, difference)``.
    literature: tuple[tuple[str, str, str, str, str], ...] = ()

    def title(self) -> str:
        return (f"Leading error terms of {len(self.rules)} mass rules, p = "
                f"{', '.join(map(str, self.degrees))}")

    def header_lines(self) -> list[str]:
        return [f"degrees: {', '.join(map(str, self.degrees))}",
                f"plate: Bloch, {self.plate_n} control points through the thickness, "
                f"r = b/H = {self.plate_r}, series to {self.series_order}",
                "bar: periodic uniform B-splines, omega_h^2/omega^2 - 1 in theta = k h"]

    def columns(self) -> tuple[str, ...]:
        return ("rule", "p", "model", "power", "coefficient", "consistent power", "keeps order")

    def rows(self) -> list[dict]:
        return [asdict(r) for r in self.terms]

    def to_json(self) -> str:
        """:meth:`to_dict` as strict JSON text."""
        import json

        from dispersion.results import jsonable

        return json.dumps(jsonable(self.to_dict()), indent=1, allow_nan=False) + "\n"

    def to_dict(self) -> dict:
        out = asdict(self)
        out["terms"] = self.rows()
        out["failures"] = list(self.failures)
        return out

    def __repr__(self) -> str:
        return (f"LumpingOrders({len(self.terms)} leading terms: {len(self.rules)} rules, "
                f"p = {self.degrees})")


def _plate_key(rule, p: int):
    import sympy

    from dispersion.symbolic.plate import plate_patch

    n = max(p + 1, 3)
    pp = plate_patch(p, n, "bloch", sympy.Rational(2, n - p), rule)
    return (tuple(pp.My), pp.x_mass, pp.x_stiffness)


def lumping_orders(degrees=(1, 2, 3, 4), rules=None, *, bar: bool = True,
                   plate: bool = True) -> LumpingOrders:
    """The table of leading error terms (module docstring)."""
    from dispersion.errors import InputError
    from dispersion.mass_rules.rule_families import approximate_dual_rule
    from dispersion.mass_rules.mass_rule import RULE_NAMES, get_rule

    t0 = time.perf_counter()
    if rules is None:
        rules = RULE_NAMES + ("dual-lumped-q1",)
    named = {"dual-lumped-q1": approximate_dual_rule(1)}
    objs = {name: named.get(name) or get_rule(name) for name in rules}
    if not degrees or any(not isinstance(p, int) or not 1 <= p <= 4 for p in degrees):
        raise InputError(f"degrees must be integers in [1, 4], got {degrees!r}")
    rows, failures = [], []
    for p in degrees:
        order = 2 * p + 4
        results: dict[str, dict[str, tuple]] = {}
        plate_cache: dict = {}
        for name, rule in objs.items():
            res: dict[str, tuple] = {}
            if bar and not rule.redistributes:
                res["bar"] = bar_leading_term(rule, p, order)
            if plate and rule.basis == "bspline":  # C0 Lagrange: the bar only (p DOFs a cell)
                try:
                    key = _plate_key(rule, p)
                    if key not in plate_cache:  # rules with the same matrices share a series
                        plate_cache[key] = plate_leading_terms(rule, p, order)
                    res.update(plate_cache[key])
                except InputError as exc:  # e.g. a rule refused on this patch
                    failures.append(f"{name} p={p} plate: {exc}")
            results[name] = res
        ref = results.get("consistent") or {
            k: v for k, v in (("bar", bar_leading_term("consistent", p, order)),) if bar}
        if plate and "plate S0" not in ref:
            ref.update(plate_leading_terms("consistent", p, order))
        for name, res in results.items():
            for model, (k, c) in res.items():
                kc = ref.get(model, (None, ""))[0]
                keeps = (k is None) or (kc is not None and k >= kc)
                rows.append(OrderRow(name, p, model, k, c, kc, keeps))
    info = tuple((name, rule.description, rule.explicit_cost.describe())
                 for name, rule in objs.items())
    return LumpingOrders(tuple(degrees), tuple(rules), "2/(n - p)", "max(p + 1, 3)",
                         "kappa^(2p + 4)", tuple(rows), time.perf_counter() - t0,
                         tuple(failures), info)


#: The claims files of the lumping literature, relative to the checkout root.
LITERATURE = "examples/literature"


def literature_claims(folder=None) -> tuple[tuple[tuple[str, str, str, str, str], ...],
                                           tuple[str, ...]]:
    """Verify every ``*.toml`` of ``folder`` (default :data:`LITERATURE` of the checkout):
    rows ``(file, claim, source, status, difference)`` and the failures (files not found)."""
    from pathlib import Path

    from dispersion.claims.verify import verify_claims
    from dispersion.claims.schema import load_claims

    root = Path(__file__).resolve().parents[2]
    folder = root / LITERATURE if folder is None else Path(folder)
    files = sorted(folder.glob("*.toml")) if folder.is_dir() else []
    if not files:
        return (), (f"no claims files in {LITERATURE} (an installed package without the "
                    "examples)",)
    rows = []
    for path in files:
        result = verify_claims(load_claims(path), jobs=1)
        rows += [(path.name, r.name, r.source or "", r.status, r.difference or "")
                 for r in result.results]
    return tuple(rows), ()


def measure(quick: bool = False, executor=None) -> LumpingOrders:
    """The report's measurement: p = 1..4 (quick: 1..2), every rule, bar and plate, and the
    literature's claims files verified."""
    import dataclasses

    del executor  # seconds in-process
    res = lumping_orders((1, 2) if quick else (1, 2, 3, 4))
    rows, failures = literature_claims()
    return dataclasses.replace(res, literature=rows, failures=res.failures + failures)
