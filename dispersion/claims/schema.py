"""Claims files read into values: TOML -> :class:`~dispersion.claims.claim.Claim`, every field checked.

A claims file is untrusted text, read within the limits of
:mod:`dispersion.claims.claims_file` (a regular UTF-8 file of bounded size and nesting).
Every field is then checked for its type and range here and refused with one
:class:`~dispersion.errors.InputError` naming file, line, entry and field. The model keys
become one value, a :class:`dispersion.symbolic.patch.Patch` (or the exact plate, or the
periodic bar), in :mod:`dispersion.claims.claim_model`; expressions and numbers go through
:mod:`dispersion.claims.reader` (a whitelist, never evaluated, see
:mod:`dispersion.claims.claim_fields`); the derivation a claim asks for is bounded by the
toolkit's own limits (:func:`dispersion.symbolic.power_balance.check_request`,
:func:`dispersion.symbolic.patch.check_size`) before any work starts.
"""
from __future__ import annotations

import math
import re

import sympy

from dispersion.budget import check_claim
from dispersion.claims import explicit, mesh_claims, orders, reader
from dispersion.claims.claim import Claim
from dispersion.claims.claim_model import PATCH_KEYS, check_patch, claim_model
from dispersion.claims.claims_file import Lines, paper_claims_path, read_text, read_toml
from dispersion.claims.exact_model import EXACT, ExactModel
from dispersion.claims.claim_fields import expression, number, rational, shown
from dispersion.claims.report import readable
from dispersion.errors import InputError, did_you_mean
from dispersion.symbolic.patch import Patch
from dispersion.symbolic.power_balance import BRANCHES, NU, R_SYM

__all__ = ["KINDS", "KAPPA", "KIND_FIELDS", "CLAIM_KEYS", "TOP_KEYS", "MAX_VALUE",
           "KIND_PARSERS", "load_claims", "parse_claims",
           # where they are read, here for the readers of this module's documentation
           "EXACT", "Claim", "paper_claims_path"]

KINDS = ("series", "error_order", "value", *explicit.KINDS, *orders.KINDS, *mesh_claims.KINDS)
KAPPA = sympy.Symbol("kappa")
#: The keys that belong to one kind of claim only (a claim of another kind refuses them).
KIND_FIELDS = {"series": ("syntax", "coefficients", "series", "nu", "rtol"),
               "error_order": ("error_order", "bound"),
               "value": ("kappa", "nu", "omega", "rtol"),
               **explicit.KIND_FIELDS, **orders.KIND_FIELDS, **mesh_claims.KIND_FIELDS}
_KIND_KEYS = {key for keys in KIND_FIELDS.values() for key in keys}
CLAIM_KEYS = {"name", "source", "note", "kind", "branch", "model", *PATCH_KEYS, "expect",
              *_KIND_KEYS}
TOP_KEYS = ("title", "format", "defaults", "claim")
#: Value claims: the largest kappa and Omega (the exact tracer scans Omega up to 2 Omega + 1;
#: the CLI's ``branches --omega-max`` stops at 200 for the same reason).
MAX_VALUE = 200.0


def load_claims(path) -> list[Claim]:
    """Read and check a claims file; raise :class:`InputError` naming file, line, entry, field."""
    return parse_claims(read_text(path), str(path))


def parse_claims(text: str, file: str = "<string>") -> list[Claim]:
    """Parse the TOML text of a claims file (see :mod:`dispersion.claims`)."""
    data = read_toml(text, file)
    lines = Lines(text, file)
    unknown = set(data) - set(TOP_KEYS)
    if unknown:
        key = sorted(unknown)[0]
        raise InputError(f"{lines.top(key)}: unknown key {shown(key)} (allowed: "
                         f"{', '.join(TOP_KEYS)}){did_you_mean(key, TOP_KEYS)}")
    if "title" in data and not isinstance(data["title"], str):
        raise InputError(f"{lines.top('title')}: title must be a string, got "
                         f"{shown(data['title'])}")
    if "format" in data and (type(data["format"]) is not int or data["format"] != 1):
        raise InputError(f"{lines.top('format')}: format must be 1, got "
                         f"{shown(data['format'])}")
    base = data.get("defaults", {})
    if not isinstance(base, dict) or "name" in base or set(base) - CLAIM_KEYS:
        bad = "name" if isinstance(base, dict) and "name" in base else (
            sorted(set(base) - CLAIM_KEYS)[0] if isinstance(base, dict) else "defaults")
        raise InputError(f"{lines.top('defaults')}: [defaults] may hold claim keys except "
                         f"name (field {shown(bad)})")
    entries = data.get("claim", [])
    if not isinstance(entries, list) or not entries:
        raise InputError(f"{file}: no [[claim]] entries")
    claims, names = [], set()
    for i, entry in enumerate(entries):
        if not isinstance(entry, dict):
            raise InputError(f"{lines.at(i)}: claim #{i + 1} must be a table ([[claim]])")
        claim = _claim({**base, **entry}, entry, i, lines)
        if claim.name in names:
            raise InputError(f"{lines.at(i, 'name')}: claim {claim.name!r}: field 'name': "
                             "used twice in the file")
        names.add(claim.name)
        claims.append(claim)
    return claims


# --------------------------------------------------------------------------- fields

def _claim(entry: dict, own: dict, i: int, lines: Lines) -> Claim:
    name = own.get("name")
    where = lines.at(i)
    if not isinstance(name, str) or not name.strip():
        raise InputError(f"{where}: claim #{i + 1}: field 'name': required (a non-empty string)")

    def fail(key, message):
        line = lines.line(i, key)
        if key.isdigit() and line == lines.line(i):  # a power inside an inline table
            line = lines.line(i, "coefficients")
        raise InputError(f"{lines.file}:{line}: claim {name!r}: field {shown(key)}: {message}")

    unknown = sorted(set(entry) - CLAIM_KEYS)
    if unknown:
        fail(unknown[0], f"unknown key (allowed: {', '.join(sorted(CLAIM_KEYS))})"
                         + did_you_mean(unknown[0], CLAIM_KEYS))
    for key in ("kind", "branch", "model", "expect", "syntax", "source", "note", "mass",
                "contact", "series"):
        if key in entry and not isinstance(entry[key], str):
            fail(key, f"must be a string, got {shown(entry[key])}")
    kind = entry.get("kind", "series")
    if kind not in KINDS:
        fail("kind", f"must be one of {', '.join(KINDS)}, got {shown(kind)}")
    dynamic = kind in explicit.KINDS or kind in orders.KINDS or kind in mesh_claims.KINDS
    branch = entry.get("branch")
    if dynamic:  # checked with the model (the bar has one branch)
        branch = str(entry.get("branch", "-"))[:20]
    elif not isinstance(branch, str) or not (
            re.fullmatch(r"[SA]\d{1,3}", branch) if kind == "value" else branch in BRANCHES):
        fail("branch", "must be S0 or A0" + (" (or S1, A1, ...)" if kind == "value" else "")
             + f", got {shown(branch)}")
    if kind in orders.KINDS:  # the square-element patch of the claim's top degree
        entry = orders.prepare(entry, fail)
    model = claim_model(entry, own, fail, bar=dynamic)
    if dynamic and isinstance(model, ExactModel):
        fail("model", f"a {kind} claim needs a discretisation: a patch or 'bar'")
    expect = entry.get("expect", "holds")
    if expect not in ("holds", "differs"):
        fail("expect", f"must be 'holds' or 'differs', got {shown(expect)}")
    for key in sorted(_KIND_KEYS - set(KIND_FIELDS[kind])):
        if key in own:
            fail(key, f"not a field of a {kind} claim")
    common = dict(name=name, kind=kind, branch=branch, model=model, file=lines.file,
                  line=lines.line(i), source=entry.get("source"), note=entry.get("note"),
                  expect=expect)
    claim = KIND_PARSERS[kind](entry, common, fail)
    check_patch(model, entry, fail)
    try:  # the work a claim asks for is bounded before any derivation (dispersion.budget)
        check_claim(claim)
    except InputError as exc:
        fail("p", f"the derivation would be too large: {exc}")
    return claim


def _error_order_claim(entry: dict, common: dict, fail) -> Claim:
    if isinstance(common["model"], ExactModel):
        fail("model", "an error order compares a patch with the exact model: give a patch")
    m = entry.get("error_order")
    if type(m) is not int or m < 2 or m % 2:
        fail("error_order", f"must be an even integer >= 2, got {shown(m)}")
    bound = entry.get("bound", False)
    if not isinstance(bound, bool):
        fail("bound", "must be true or false")
    claim = Claim(**common, error_order=m, bound=bound, written=f"O(kappa^{m})")
    _check_work(claim, "error_order", fail)
    return claim


def _check_work(claim: Claim, key: str, fail) -> None:
    """Refuse a derivation beyond the engine's stated limits, before any work."""
    from dispersion.symbolic.power_balance import check_request

    try:
        exact = isinstance(claim.model, ExactModel)
        check_request(claim.branch, claim.order, exact=exact, n=None if exact else claim.model.n)
        if claim.kind == "error_order":
            check_request(claim.branch, claim.order, exact=True)
    except InputError as exc:
        word = "n" if "control points" in str(exc) else key
        fail(word, f"the derivation would be too large: {exc}")


def _value_claim(entry: dict, common: dict, fail) -> Claim:
    model = common["model"]
    values = {}
    for key in ("kappa", "nu", "omega", "rtol"):
        if key not in entry:
            fail(key, "required for a value claim: a number")
        q = number(entry[key], key, fail)
        values[key] = float(q) if abs(q) < 10**300 else math.inf
    if not (-1 < values["nu"] < 0.5):
        fail("nu", f"must lie in (-1, 0.5), got {values['nu']}")
    for key in ("kappa", "omega"):
        if not 0 <= values[key] <= MAX_VALUE or (key == "omega" and values[key] == 0):
            fail(key, f"must lie in {'[0' if key == 'kappa' else '(0'}, {MAX_VALUE:g}], "
                      f"got {values[key]:g}")
    if not 0 < values["rtol"] < 1:
        fail("rtol", f"must lie in (0, 1), got {values['rtol']:g}")
    if isinstance(model, Patch) and model.symbolic_r:
        fail("r", "a value claim needs a number for the aspect ratio r")
    return Claim(**common, written=f"Omega({values['kappa']:g}) = {values['omega']:.12g}",
                 **values)


def _series_claim(entry: dict, common: dict, fail) -> Claim:
    syntax = entry.get("syntax", "sympy")
    if syntax not in reader.SYNTAXES:
        fail("syntax", f"must be 'sympy' or 'latex', got {shown(syntax)}")
    has_c, has_s = "coefficients" in entry, "series" in entry
    if has_c == has_s:
        fail("coefficients", "give either a coefficients table or a series expression")
    branch = common["branch"]
    sigma = BRANCHES[branch][1]
    exact = isinstance(common["model"], ExactModel)
    from dispersion.symbolic.power_balance import MAX_ORDER

    top_order = MAX_ORDER["exact" if exact else "discrete"]
    rule = (f"power of kappa must be an even integer in [{2 * sigma}, {top_order}] for "
            f"{branch}")
    if has_c:
        table = entry["coefficients"]
        if not isinstance(table, dict) or not table:
            fail("coefficients", "must be a table {power of kappa: coefficient}")
        printed = {}
        for k, text in table.items():
            # canonical decimal only: "02" and "2" would be one power twice
            if not re.fullmatch(r"[1-9]\d{0,2}", k) or int(k) < 2 * sigma or int(k) % 2 \
                    or int(k) > top_order:
                fail(k, f"{rule}, written without leading zeros; got {shown(k)}")
            expr = expression(text, k, syntax, fail)
            if KAPPA in expr.free_symbols or expr.has(sympy.Order):
                fail(k, "a coefficient must not contain kappa")
            printed[int(k)] = expr
        written = "; ".join(f"kappa^{k}: {v}" for k, v in table.items())
    else:
        text = entry["series"]
        if not text.strip():
            fail("series", "must be an expression (a string), got an empty one")
        try:
            found, order = reader.read_series(text, syntax)
        except InputError as exc:
            what = "LaTeX" if syntax == "latex" else "sympy text"
            fail("series", f"{exc} (reading {what} {shown(text)})")
        bad = sorted(k for k in found if k < 2 * sigma or k % 2 or k > top_order)
        if bad:
            fail("series", f"{rule}, got kappa^{bad[0]}")
        if order is not None:
            top = order - 1
            if top > top_order:
                fail("series", f"order term O(kappa^{order}) beyond the highest power "
                               f"{top_order} derived for {branch}")
        else:
            top = max(found, default=0)
        powers = set(found) | set(range(2 * sigma, top + 1, 2))
        if not powers:
            fail("series", "claims no power of kappa")
        printed = {k: readable(found.get(k, sympy.Integer(0))) for k in sorted(powers)}
        written = text
    nu = entry.get("nu")
    if nu is not None:
        nu = rational(nu, "nu", fail)
        if not (-1 < nu < sympy.Rational(1, 2)):
            fail("nu", f"must lie in (-1, 0.5), got {nu}")
        printed = {k: v.subs(NU, nu) for k, v in printed.items()}
    rtol = entry.get("rtol")
    if rtol is not None:
        if nu is None:
            fail("rtol", "a tolerance on series coefficients needs a number for nu")
        q = number(rtol, "rtol", fail)
        if not 0 < q < 1:
            fail("rtol", f"must lie in (0, 1), got {shown(rtol)}")
        rtol = float(q)
    model = common["model"]
    allowed = {NU, R_SYM} if isinstance(model, Patch) and model.symbolic_r else {NU}
    for k, v in printed.items():
        extra = v.free_symbols - allowed
        if extra:
            fail(str(k) if has_c else "series",
                 f"symbol {sorted(map(str, extra))[0]!r} is not a parameter of this model")
        if rtol is not None and not v.is_number:
            fail(str(k) if has_c else "series", "a tolerance needs numbers: the coefficient "
                                                 f"still holds {sorted(map(str, v.free_symbols))}")
    claim = Claim(**common, printed=tuple(sorted(printed.items())), written=written, nu=nu,
                  rtol=rtol)
    _check_work(claim, "coefficients" if has_c else "series", fail)
    return claim


#: The parser of each kind of claim: ``(merged entry, common fields, fail) -> Claim``. A new
#: kind adds its name to :data:`KINDS`, its own keys to :data:`KIND_FIELDS`, a parser here
#: and its derivation and verdict in :data:`dispersion.claims.verify.KIND_RULES`.
KIND_PARSERS = {"series": _series_claim, "error_order": _error_order_claim,
                "value": _value_claim, "critical_step": explicit.step_claim,
                "fully_discrete_series": explicit.series_claim,
                "order_range": orders.order_claim, "leading_term": orders.leading_claim,
                "mesh_step": mesh_claims.mesh_claim}
