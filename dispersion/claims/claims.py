"""Claims about dispersion branches, written as data and checked against the derivation.

A *claim* is what a paper, a manuscript or a textbook states about a branch of a model: its
power series (eqs 14-20 of the paper are such claims), the leading order of its error, or its
value at one wavenumber. A claims file is TOML::

    title = "My manuscript"           # optional
    [defaults]                        # optional: keys every claim inherits
    model = "bloch"

    [[claim]]
    name = "S0 bar speed"             # required, unique in the file
    source = "Smith 2024, eq (3)"     # optional: paper and equation
    branch = "S0"                     # S0 or A0 (value claims: S0, S1, ..., A0, A1, ...)
    model = "rayleigh-lamb"           # or a patch: "bloch" / "x-exact" with the keys below
    [claim.coefficients]              # Omega^2 = sum of coefficient * kappa^power
    2 = "2/(1 - nu)"

Keys of a claim (``[defaults]`` may set any of them except ``name``):

``kind``
    ``"series"`` (default), ``"error_order"`` or ``"value"``.
``model``
    ``"rayleigh-lamb"`` (the exact plate, eq 13 in its standard form) or a plate patch,
    ``"bloch"`` or ``"x-exact"`` (:func:`dispersion.symbolic.plate.plate_patch`) with ``p``, ``n``,
    ``r`` (number, ``"1/2"`` or ``"r"`` for the symbol), ``mass``, ``contact``, ``gamma_s``
    and ``weights`` (a table ``{contact index: {neighbour index: weight}}``). Unset patch
    keys take the toolkit's defaults (:mod:`dispersion.defaults`).
``coefficients`` or ``series`` (series claims)
    Either a table power -> coefficient of :math:`\\Omega^2` (each power listed is claimed),
    or the whole expression in ``kappa``, e.g. ``"2/(1-nu)*kappa^2 + O(kappa^4)"``: every
    even power from the branch's first up to the order term (or the highest power written)
    is claimed, a missing one as zero.
``syntax``
    ``"sympy"`` (default: sympy text, ``^`` or ``**`` for powers, symbols ``nu``, ``kappa``,
    ``r``) or ``"latex"`` (``\\nu``, ``\\kappa``, ``\\frac``, ``O(\\kappa^8)``, as printed in a
    paper; parsed by sympy's ``parse_latex`` with the ``lark`` backend, products before an
    opening and after a closing parenthesis made explicit first). Use TOML literal strings
    (single quotes) so that backslashes stay as written.
``nu``, ``rtol``
    Series claims may substitute a number for nu (``nu = "3/10"``); with ``rtol`` as well,
    the coefficients are compared to that relative tolerance instead of exactly.
``error_order``, ``bound``
    Error-order claims: the leading power of kappa of :math:`\\Omega_h^2 - \\Omega^2` (the
    patch's series minus the exact Rayleigh-Lamb series). Exact by default; with
    ``bound = true`` the claim is "O(kappa^error_order)", i.e. that power or a higher one.
``kappa``, ``nu``, ``omega``, ``rtol``
    Value claims: :math:`\\Omega` of the branch at :math:`\\kappa` and nu, within ``rtol``.
``expect``
    ``"holds"`` (default) or ``"differs"``: a recorded finding that the claim does *not*
    hold under these settings (like pytest's strict ``xfail``: it fails if it holds).
``source``, ``note``
    Free text shown in the reports.

Comparisons are exact: the printed minus the derived coefficient, cancelled over QQ(nu[, r]),
must be zero. A mismatch is described as simply as possible: a sign, a constant factor, a
changed term of the numerator, or the difference itself.

>>> claims = parse_claims('''
... [[claim]]
... name = "A0 leading"
... branch = "A0"
... model = "rayleigh-lamb"
... coefficients = {4 = "2/(3*(1 - nu))"}
... ''')
>>> check_claim(claims[0]).status
'holds'

References
----------
A. Tkachuk, M. Matzen, R. Kolman, M. Bischoff, eqs (13)-(20).
"""
from __future__ import annotations

import functools
import re
import time
from dataclasses import dataclass, field
from pathlib import Path
from xml.etree import ElementTree as ET

import sympy

from dispersion import defaults
from dispersion.errors import DispersionError, InputError, check_int_in_range
from dispersion.symbolic.power_balance import BRANCHES, NU, R_SYM

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = [
    "EXACT", "KINDS", "KAPPA", "Model", "Claim", "Term", "ClaimResult", "Verification",
    "parse_claims", "load_claims", "check_claim", "verify_claims", "verify_file",
    "describe_difference", "format_results", "junit_xml", "paper_claims_path", "MAX_JOBS",
    "check_jobs",
]

#: Name of the exact model (the Rayleigh-Lamb equation of :mod:`dispersion.waves.rayleigh_lamb`).
EXACT = "rayleigh-lamb"
KINDS = ("series", "error_order", "value", "critical_step", "fully_discrete_series")
KAPPA = sympy.Symbol("kappa")
PATCH_KEYS = ("p", "n", "r", "mass", "contact", "gamma_s", "weights")
CLAIM_KEYS = {"name", "source", "note", "kind", "branch", "model", *PATCH_KEYS, "syntax",
              "coefficients", "series", "nu", "rtol", "error_order", "bound", "kappa",
              "omega", "expect", "ratio", "omega_max", "scheme"}
#: Most worker processes :func:`verify_claims` starts. A worker is a Python process holding
#: sympy and its caches: ``verify --paper`` in one process peaks at 110 MiB resident, so 64
#: workers stay under a third of this machine's 24 GiB, and on its 2 cores more workers than
#: derivations or cores only add start-up time.
MAX_JOBS = 64
_NAMES = {"nu": NU, "r": R_SYM, "kappa": KAPPA}
_FUNCTIONS = {"sqrt": sympy.sqrt, "Rational": sympy.Rational, "O": sympy.Order}


@dataclass(frozen=True)
class Model:
    """A model the toolkit derives: the exact plate (``name == EXACT``) or a plate patch.

    Hashable, so each distinct model and branch is derived once.

    >>> Model("bloch", r=2).label()
    'bloch p=2 n=3 r=2, consistent mass'
    """

    name: str
    p: int = defaults.P
    n: int = defaults.N
    r: object = defaults.R
    mass: str = defaults.MASS
    contact: str = defaults.CONTACT
    gamma_s: object = defaults.GAMMA_S
    weights: tuple | None = None  # ((contact, ((neighbour, weight), ...)), ...)

    @property
    def exact(self) -> bool:
        return self.name == EXACT

    def patch_kwargs(self) -> dict:
        """Keywords of :func:`dispersion.symbolic.plate.plate_patch` / ``discrete_series``."""
        kw = dict(p=self.p, n=self.n, model=self.name, r=self.r, mass=self.mass)
        if self.mass.startswith("singular"):
            kw.update(contact=self.contact, gamma_s=self.gamma_s)
            if self.weights is not None:
                kw["weights"] = {c: dict(ws) for c, ws in self.weights}
        return kw

    def label(self) -> str:
        """Short description, e.g. ``bloch p=2 n=3 r=2, singular mass (top, gamma_s=0)``."""
        if self.exact:
            return "Rayleigh-Lamb (exact)"
        if self.name == "bar":
            return f"periodic bar p={self.p}, {self.mass} mass"
        geom = f"{self.name} p={self.p} n={self.n}" + (f" r={self.r}" if self.name == "bloch"
                                                        else "")
        mass = f"{self.mass} mass"
        if self.mass.startswith("singular"):
            mass += (f" (weights {self.patch_kwargs()['weights']})" if self.weights is not None
                     else f" ({self.contact}, gamma_s={self.gamma_s})")
        return f"{geom}, {mass}"


@dataclass(frozen=True)
class Claim:
    """One claim of a claims file (see the module docstring for its fields)."""

    name: str
    kind: str
    branch: str
    model: Model
    file: str = "<string>"
    line: int = 0
    source: str | None = None
    note: str | None = None
    printed: tuple = ()  # series: ((power, coefficient), ...)
    written: str = ""  # the claim as written in the file
    nu: object = None
    rtol: float | None = None
    error_order: int | None = None
    bound: bool = False
    kappa: float | None = None
    omega: float | None = None
    expect: str = "holds"

    @property
    def order(self) -> int:
        """Highest power of kappa the derivation must reach."""
        if self.kind == "error_order":
            return self.error_order + 2
        return max((k for k, _ in self.printed), default=2 * BRANCHES[self.branch][1])


@dataclass(frozen=True)
class Term:
    """One power of kappa of a series claim, printed beside derived."""

    power: int
    printed: sympy.Expr
    derived: sympy.Expr
    holds: bool
    difference: str


@dataclass(frozen=True)
class ClaimResult:
    """A checked claim: what was printed, what the derivation gives, and the verdict.

    ``status`` is ``"holds"``, ``"differs"``, ``"differs (expected)"`` (a recorded finding),
    ``"holds (unexpected)"`` or ``"error"``; ``passed`` is True for the first and third.
    """

    name: str
    source: str | None
    kind: str
    branch: str
    model: str
    file: str
    line: int
    printed: str
    derived: str
    status: str
    passed: bool
    difference: str
    terms: tuple[Term, ...] = ()
    printed_latex: str = ""
    derived_latex: str = ""
    note: str | None = None


@dataclass(frozen=True)
class Verification:
    """Every claim of one or more files, checked; ``passed`` if each holds as expected."""

    files: tuple[str, ...]
    results: tuple[ClaimResult, ...]
    seconds: float
    passed: bool = field(init=False)

    def __post_init__(self):
        object.__setattr__(self, "passed", all(r.passed for r in self.results))


# --------------------------------------------------------------------------- reading

def paper_claims_path() -> Path:
    """The claims file of the paper's eqs (14)-(20) shipped with the package."""
    from importlib import resources

    return Path(str(resources.files("dispersion") / "data" / "paper_claims.toml"))


def load_claims(path) -> list[Claim]:
    """Read and check a claims file; raise :class:`InputError` naming file, line, entry, field."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise InputError(f"{path}: cannot read claims file ({exc.strerror})") from None
    return parse_claims(text, str(path))


def parse_claims(text: str, file: str = "<string>") -> list[Claim]:
    """Parse the TOML text of a claims file (see the module docstring)."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{file}: malformed TOML: {exc}") from None
    lines = _Lines(text, file)
    unknown = set(data) - {"title", "format", "defaults", "claim"}
    if unknown:
        key = sorted(unknown)[0]
        raise InputError(f"{lines.top(key)}: unknown key {key!r} (allowed: title, format, "
                         "defaults, claim)")
    base = data.get("defaults", {})
    if not isinstance(base, dict) or "name" in base or set(base) - CLAIM_KEYS:
        bad = "name" if isinstance(base, dict) and "name" in base else "defaults"
        raise InputError(f"{lines.top('defaults')}: [defaults] may hold claim keys except "
                         f"name (field {bad!r})")
    entries = data.get("claim", [])
    if not isinstance(entries, list) or not entries:
        raise InputError(f"{file}: no [[claim]] entries")
    claims, names = [], set()
    for i, entry in enumerate(entries):
        claim = _claim({**base, **entry}, entry, i, lines)
        if claim.name in names:
            raise InputError(f"{lines.at(i, 'name')}: claim {claim.name!r}: field 'name': "
                             "used twice in the file")
        names.add(claim.name)
        claims.append(claim)
    return claims


class _Lines:
    """Line numbers of ``[[claim]]`` entries and their keys, for error messages."""

    def __init__(self, text: str, file: str):
        self.file = file
        self.text = text.splitlines()
        self.heads = [i for i, s in enumerate(self.text) if re.match(r"\s*\[\[\s*claim\s*\]\]", s)]

    def _find(self, key: str, lo: int, hi: int) -> int | None:
        pat = re.compile(rf"\s*(\[\s*(claim|defaults)\.)?\"?{re.escape(key)}\"?\s*(=|\])")
        return next((i for i in range(lo, hi) if pat.match(self.text[i])), None)

    def top(self, key: str) -> str:
        hit = self._find(key, 0, self.heads[0] if self.heads else len(self.text))
        return f"{self.file}:{hit + 1 if hit is not None else 1}"

    def line(self, i: int, key: str | None = None) -> int:
        lo = self.heads[i] if i < len(self.heads) else 0
        hi = self.heads[i + 1] if i + 1 < len(self.heads) else len(self.text)
        hit = self._find(key, lo, hi) if key else None
        return (hit if hit is not None else lo) + 1

    def at(self, i: int, key: str | None = None) -> str:
        return f"{self.file}:{self.line(i, key)}"


def _claim(entry: dict, own: dict, i: int, lines: _Lines) -> Claim:
    name = own.get("name")
    where = lines.at(i)
    if not isinstance(name, str) or not name.strip():
        raise InputError(f"{where}: claim #{i + 1}: field 'name': required (a non-empty string)")

    def fail(key, message):
        line = lines.line(i, key)
        if key.isdigit() and line == lines.line(i):  # a power inside an inline table
            line = lines.line(i, "coefficients")
        raise InputError(f"{lines.file}:{line}: claim {name!r}: field {key!r}: {message}")

    unknown = sorted(set(entry) - CLAIM_KEYS)
    if unknown:
        fail(unknown[0], f"unknown key (allowed: {', '.join(sorted(CLAIM_KEYS))})")
    kind = entry.get("kind", "series")
    if kind not in KINDS:
        fail("kind", f"must be one of {', '.join(KINDS)}, got {kind!r}")
    if kind in ("critical_step", "fully_discrete_series"):  # dispersion.claims.explicit
        return _explicit_claim(entry, own, name, kind, lines.file, lines.line(i), fail)
    branch = entry.get("branch")
    ok = (re.fullmatch(r"[SA]\d+", branch or "") if kind == "value" else branch in BRANCHES)
    if not isinstance(branch, str) or not ok:
        fail("branch", "must be S0 or A0" + (" (or S1, A1, ...)" if kind == "value" else "")
             + f", got {branch!r}")
    model = _model(entry, own, fail)
    expect = entry.get("expect", "holds")
    if expect not in ("holds", "differs"):
        fail("expect", f"must be 'holds' or 'differs', got {expect!r}")
    for key in ("source", "note"):
        if key in entry and not isinstance(entry[key], str):
            fail(key, "must be a string")
    common = dict(name=name, kind=kind, branch=branch, model=model, file=lines.file,
                  line=lines.line(i), source=entry.get("source"), note=entry.get("note"),
                  expect=expect)
    wrong = {"series": ("error_order", "bound", "kappa", "omega"),
             "error_order": ("coefficients", "series", "nu", "rtol", "kappa", "omega"),
             "value": ("coefficients", "series", "error_order", "bound")}[kind]
    for key in wrong:
        if key in own:
            fail(key, f"not a field of a {kind} claim")
    if kind == "series":
        return _series_claim(entry, common, fail)
    if model.exact:
        if kind == "error_order":
            fail("model", "an error order compares a patch with the exact model: give a patch")
    if kind == "error_order":
        m = entry.get("error_order")
        if isinstance(m, bool) or not isinstance(m, int) or m < 2:
            fail("error_order", f"must be an integer >= 2, got {m!r}")
        bound = entry.get("bound", False)
        if not isinstance(bound, bool):
            fail("bound", "must be true or false")
        return Claim(**common, error_order=m, bound=bound, written=f"O(kappa^{m})")
    values = {}
    for key, lo in (("kappa", 0.0), ("nu", None), ("omega", 0.0), ("rtol", 0.0)):
        v = entry.get(key)
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            fail(key, f"required for a value claim: a number, got {v!r}")
        values[key] = float(v)
    if not (-1 < values["nu"] < 0.5):
        fail("nu", f"must lie in (-1, 0.5), got {values['nu']}")
    for key in ("kappa", "omega", "rtol"):
        if values[key] < 0 or (key != "kappa" and values[key] == 0):
            fail(key, f"must be {'>= 0' if key == 'kappa' else '> 0'}, got {values[key]}")
    if not model.exact and model.name == "bloch" and model.r == R_SYM:
        fail("r", "a value claim needs a number for the aspect ratio r")
    return Claim(**common, written=f"Omega({values['kappa']:g}) = {values['omega']:.12g}",
                 **values)


def _explicit_claim(entry, own, name, kind, file, line, fail) -> Claim:
    from dispersion.claims import explicit

    expect = entry.get("expect", "holds")
    if expect not in ("holds", "differs"):
        fail("expect", f"must be 'holds' or 'differs', got {expect!r}")
    common = dict(name=name, kind=kind, branch=str(entry.get("branch", "-")), model=None,
                  file=file, line=line, source=entry.get("source"), note=entry.get("note"),
                  expect=expect)
    return explicit.parse(entry, own, common, fail, _model, _parse)


def _number(text, key, fail, symbol=None):
    """An exact number from a TOML int, float or string such as ``"1/2"``."""
    if isinstance(text, bool):
        fail(key, f"must be a number, got {text!r}")
    if isinstance(text, str) and symbol is not None and text.strip() == str(symbol):
        return symbol
    try:
        value = sympy.nsimplify(text) if isinstance(text, float) else sympy.Rational(text)
    except (TypeError, ValueError):
        fail(key, f"must be a number (or a fraction such as '1/2'), got {text!r}")
    return value


def _model(entry: dict, own: dict, fail) -> Model:
    name = entry.get("model", defaults.MODEL)
    if name == EXACT:  # patch keys inherited from [defaults] do not apply to it
        given = [k for k in PATCH_KEYS if k in own]
        if given:
            fail(given[0], "not a setting of the exact model (rayleigh-lamb)")
        return Model(EXACT)
    from dispersion.symbolic.plate import MODELS, plate_patch

    if name not in MODELS:
        fail("model", f"must be {EXACT!r} or a patch model ({', '.join(MODELS)}), got {name!r}")
    kw = {}
    for key in ("p", "n"):
        if key in entry:
            if isinstance(entry[key], bool) or not isinstance(entry[key], int):
                fail(key, f"must be an integer, got {entry[key]!r}")
            kw[key] = entry[key]
    for key in ("mass", "contact"):
        if key in entry:
            if not isinstance(entry[key], str):
                fail(key, f"must be a string, got {entry[key]!r}")
            kw[key] = entry[key]
    if "r" in entry:
        kw["r"] = _number(entry["r"], "r", fail, symbol=R_SYM)
    if "gamma_s" in entry:
        kw["gamma_s"] = _number(entry["gamma_s"], "gamma_s", fail)
    if "weights" in entry:
        w = entry["weights"]
        try:
            kw["weights"] = tuple(sorted((int(c), tuple(sorted((int(j), _number(v, "weights", fail))
                                                             for j, v in ws.items())))
                                         for c, ws in w.items()))
        except (AttributeError, ValueError):
            fail("weights", "must be a table {contact index: {neighbour index: weight}}")
    model = Model(name, **kw)
    if name != "bloch" and "r" in entry:
        fail("r", f"the aspect ratio belongs to the bloch model, not {name!r}")
    try:
        plate_patch(**model.patch_kwargs())
    except InputError as exc:
        words = str(exc).split(" must")[0].replace("(", " ").split()
        key = next((k for k in PATCH_KEYS if k in words and k in entry), "model")
        fail(key, f"the toolkit cannot build this patch: {exc}")
    return model


def _parse(text, key, syntax, fail) -> sympy.Expr:
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return sympy.nsimplify(text) if isinstance(text, float) else sympy.Integer(text)
    if not isinstance(text, str) or not text.strip():
        fail(key, f"must be an expression (a string), got {text!r}")
    if syntax == "latex":
        return _parse_latex(text, key, fail)
    names = set(re.findall(r"[A-Za-z_]\w*", text))
    bad = sorted(names - set(_NAMES) - set(_FUNCTIONS))
    if bad:
        fail(key, f"unknown name {bad[0]!r} in {text!r} (use nu, kappa, r, sqrt, O)")
    from sympy.parsing.sympy_parser import (convert_xor, parse_expr,
                                            standard_transformations)

    try:
        expr = parse_expr(text, local_dict={**_NAMES, **_FUNCTIONS},
                          transformations=standard_transformations + (convert_xor,))
    except Exception as exc:  # noqa: BLE001 - any parser failure is the user's input
        fail(key, f"does not parse as sympy text: {text!r} ({type(exc).__name__})")
    return sympy.sympify(expr)


def _parse_latex(text, key, fail) -> sympy.Expr:
    order = None
    m = re.search(r"\+\s*(?:\\mathcal\{O\}|O)\s*(?:\\left)?\(\s*\\kappa\s*\^\s*\{?(\d+)\}?"
                  r"\s*(?:\\right)?\)\s*$", text)
    body = text[:m.start()] if m else text
    if m:
        order = int(m.group(1))
    # the lark grammar needs explicit products before "(" and after ")": 2\nu^2(1-\nu)
    body = body.replace(r"\left", "").replace(r"\right", "")
    body = re.sub(r"(\\[A-Za-z]+|[A-Za-z0-9}])\s*\(", lambda m: m.group(0) if m.group(1) in
                  (r"\cdot", r"\times") else m.group(1) + r" \cdot (", body)
    body = re.sub(r"\)(?=\s*[A-Za-z0-9\\(])", r") \\cdot ", body)
    try:
        expr = sympy.Add(*[sign * _parse_latex_term(term) for sign, term in _terms(body)])
    except ImportError:
        fail(key, "LaTeX claims need the lark package (pip install lark)")
    except Exception as exc:  # noqa: BLE001 - any parser failure is the user's input
        fail(key, f"does not parse as LaTeX: {text!r} ({type(exc).__name__})")
    expr = expr.subs({sympy.Symbol(s): v for s, v in _NAMES.items()})
    bad = sorted(str(s) for s in expr.free_symbols - set(_NAMES.values()))
    if bad:
        fail(key, f"unknown symbol {bad[0]!r} in {text!r} (use \\nu, \\kappa, r)")
    return expr + sympy.Order(KAPPA**order) if order else expr


def _terms(body: str) -> list[tuple[int, str]]:
    """Split a LaTeX sum at its top-level + and - (the parser is superlinear in length)."""
    out, depth, start, sign = [], 0, 0, 1
    for i, ch in enumerate(body):
        depth += ch in "{(" and 1 or (ch in "})" and -1 or 0)
        if depth == 0 and ch in "+-" and body[start:i].strip():
            out.append((sign, body[start:i]))
            start, sign = i + 1, (1 if ch == "+" else -1)
        elif depth == 0 and ch in "+-":  # a leading sign
            start, sign = i + 1, sign * (1 if ch == "+" else -1)
    out.append((sign, body[start:]))
    return out


@functools.lru_cache(maxsize=1024)
def _parse_latex_term(term: str):
    from sympy.parsing.latex import parse_latex

    expr = _unambiguous(parse_latex(term, backend="lark"))
    if expr is None:
        raise ValueError("ambiguous")
    return expr


def _unambiguous(tree):
    """The one reading of a lark parse: its alternatives (``_ambig``) must all be equal.

    The lark grammar is ambiguous in the association of products (``2 x (y)``); the
    readings are then equal expressions and any will do. Returns None if they differ.
    """
    if isinstance(tree, sympy.Basic):
        return tree
    if getattr(tree, "data", None) != "_ambig":
        return None
    readings = [_unambiguous(c) for c in tree.children]
    if any(r is None for r in readings):
        return None
    first = readings[0]
    return first if all(sympy.cancel(r - first) == 0 for r in readings[1:]) else None


def _series_claim(entry: dict, common: dict, fail) -> Claim:
    syntax = entry.get("syntax", "sympy")
    if syntax not in ("sympy", "latex"):
        fail("syntax", f"must be 'sympy' or 'latex', got {syntax!r}")
    has_c, has_s = "coefficients" in entry, "series" in entry
    if has_c == has_s:
        fail("coefficients", "give either a coefficients table or a series expression")
    sigma = BRANCHES[common["branch"]][1]
    if has_c:
        table = entry["coefficients"]
        if not isinstance(table, dict) or not table:
            fail("coefficients", "must be a table {power of kappa: coefficient}")
        printed = {}
        for k, text in table.items():
            if not re.fullmatch(r"\d+", k) or int(k) < 2 * sigma or int(k) % 2:
                fail(k, f"power of kappa must be an even integer >= {2 * sigma} for "
                        f"{common['branch']}, got {k!r}")
            expr = _parse(text, k, syntax, fail)
            if KAPPA in expr.free_symbols or expr.has(sympy.Order):
                fail(k, "a coefficient must not contain kappa")
            printed[int(k)] = expr
        written = "; ".join(f"kappa^{k}: {v}" for k, v in table.items())
    else:
        expr = _parse(entry["series"], "series", syntax, fail)
        order_term = expr.getO()
        expr = expr.removeO()
        try:
            poly = sympy.Poly(expr, KAPPA)
        except sympy.PolynomialError:
            fail("series", "must be a polynomial in kappa (plus an optional O(kappa^k) term)")
        powers = {m[0] for m in poly.monoms()}
        if order_term is not None:
            top = sympy.degree(order_term.expr, KAPPA) - 1
        else:
            top = max(powers, default=0)
        powers |= set(range(2 * sigma, top + 1, 2))
        if not powers:
            fail("series", "claims no power of kappa")
        printed = {k: sympy.factor(poly.coeff_monomial(KAPPA**k)) for k in sorted(powers)}
        written = entry["series"]
    nu = entry.get("nu")
    if nu is not None:
        nu = _number(nu, "nu", fail)
        if not (-1 < nu < sympy.Rational(1, 2)):
            fail("nu", f"must lie in (-1, 0.5), got {nu}")
        printed = {k: v.subs(NU, nu) for k, v in printed.items()}
    rtol = entry.get("rtol")
    if rtol is not None:
        if nu is None:
            fail("rtol", "a tolerance on series coefficients needs a number for nu")
        if isinstance(rtol, bool) or not isinstance(rtol, (int, float)) or rtol <= 0:
            fail("rtol", f"must be a number > 0, got {rtol!r}")
        rtol = float(rtol)
    allowed = {NU, R_SYM} if common["model"].r == R_SYM else {NU}
    for k, v in printed.items():
        extra = v.free_symbols - allowed
        if extra:
            fail(str(k) if has_c else "series",
                 f"symbol {sorted(map(str, extra))[0]!r} is not a parameter of this model")
    return Claim(**common, printed=tuple(sorted(printed.items())), written=written, nu=nu,
                 rtol=rtol)


# --------------------------------------------------------------------------- deriving

@functools.lru_cache(maxsize=64)
def _series(model: Model, branch: str, order: int) -> dict[int, sympy.Expr]:
    """Derived series of ``branch`` of ``model`` to kappa^order (cached per process)."""
    from dispersion.symbolic.power_balance import discrete_series
    from dispersion.waves.exact_series import exact_series

    if model.exact:
        return exact_series(branch, order)
    return discrete_series(branch, order, **model.patch_kwargs())


def _omega(model: Model, branch: str, kappa: float, nu: float, guess: float) -> float:
    """Omega of ``branch`` at one kappa (NaN if it does not exist below 2 guess + 1)."""
    if model.exact:
        from dispersion.waves.exact_branches import trace_branches

        br = trace_branches(nu, [kappa], 2 * guess + 1)
    else:
        from dispersion.waves.discrete_branches import discrete_branches
        from dispersion.symbolic.plate import plate_patch

        br = discrete_branches(plate_patch(**model.patch_kwargs()), nu, [kappa])
    return float(br.omega[branch][0]) if branch in br.omega else float("nan")


def _task(claim: Claim) -> list[tuple]:
    """The derivations a claim needs (shared between claims with equal tasks)."""
    if claim.kind in ("critical_step", "fully_discrete_series"):
        from dispersion.claims import explicit

        return [explicit.task(claim)]
    if claim.kind == "value":
        return [("value", claim.model, claim.branch, claim.kappa, claim.nu, claim.omega)]
    tasks = [("series", claim.model, claim.branch, claim.order)]
    if claim.kind == "error_order":
        tasks.append(("series", Model(EXACT), claim.branch, claim.order))
    return tasks


def _run_task(task: tuple):
    if task[0] in ("critical_step", "fully_discrete_series"):
        from dispersion.claims import explicit

        return explicit.run(task)
    if task[0] == "series":
        return _series(*task[1:])
    return _omega(*task[1:])


def _same(a, b) -> bool:
    return sympy.cancel(sympy.together(a - b)) == 0


def _show(expr) -> str:
    """``1 - nu`` rather than sympy's ``-nu + 1``."""
    const, rest = sympy.expand(expr).as_coeff_Add()
    return f"{const} - {-rest}" if const and rest.could_extract_minus_sign() else str(expr)


def _numer_terms(expr) -> dict:
    num = sympy.Poly(expr, *sorted(expr.free_symbols, key=str)) if expr.free_symbols else None
    return dict(num.terms()) if num is not None else {(): expr}


def describe_difference(printed, derived) -> str:
    """The simplest description of ``printed`` against ``derived`` ('' if they are equal).

    >>> nu = sympy.Symbol("nu")
    >>> describe_difference(-2/(1 - nu), 2/(1 - nu))
    'sign: printed = -(derived)'
    >>> describe_difference(1/(1 - nu), 2/(1 - nu))
    'factor: printed = 1/2 * derived'
    >>> describe_difference((nu + 3)/(1 - nu), (nu + 2)/(1 - nu))
    'numerator term 2 -> 3 (same denominator 1 - nu)'
    """
    printed, derived = sympy.sympify(printed), sympy.sympify(derived)
    diff = sympy.factor(sympy.cancel(printed - derived))
    if diff == 0:
        return ""
    if derived == 0:
        return f"extra term: printed {printed}, derived 0"
    if printed == 0:
        return f"missing term: derived {derived}"
    ratio = sympy.cancel(printed / derived)
    if ratio.is_number:
        return "sign: printed = -(derived)" if ratio == -1 else f"factor: printed = {ratio} * derived"
    pn, pd = sympy.fraction(sympy.cancel(printed))
    dn, dd = sympy.fraction(sympy.cancel(derived))
    q = sympy.cancel(pd / dd)
    if q.is_number:  # same denominator up to a constant: compare the numerators term by term
        pn, pd = sympy.expand(pn / q), sympy.expand(pd / q)
        if sympy.expand(pd).as_coeff_Add()[0] < 0:  # write 1 - nu rather than nu - 1
            pn, pd, dn = -pn, sympy.expand(-pd), -dn
        a, b = _numer_terms(sympy.expand(pn)), _numer_terms(sympy.expand(dn))
        changed = [m for m in set(a) | set(b) if a.get(m, 0) != b.get(m, 0)]
        if len(changed) == 1:
            m = changed[0]
            syms = sorted(sympy.expand(pn + dn).free_symbols, key=str)
            mono = sympy.Mul(*[s**e for s, e in zip(syms, m)])
            was, now = b.get(m, 0) * mono, a.get(m, 0) * mono
            return f"numerator term {was} -> {now} (same denominator {_show(sympy.factor(pd))})"
        return (f"numerator: printed {sympy.factor(pn)}, derived {sympy.factor(dn)} "
                f"(same denominator {sympy.factor(dd)})")
    k = sympy.cancel(pn / dn)
    if k.is_number:  # same numerator up to a constant: the denominators differ
        pd, dd = sympy.expand(pd / k), sympy.expand(dd)
        if dd.as_coeff_Add()[0] < 0:
            pd, dd = -pd, -dd
        return f"denominator: printed {_show(sympy.factor(pd))}, derived {_show(sympy.factor(dd))}"
    return f"difference printed - derived = {diff}"


def _series_verdict(claim: Claim, derived: dict) -> tuple[tuple[Term, ...], str]:
    terms = []
    for power, printed in claim.printed:
        ours = derived.get(power, sympy.Integer(0))
        if claim.nu is not None:
            ours = sympy.factor(ours.subs(NU, claim.nu))
        if claim.rtol is not None:
            p, d = float(printed), float(ours)
            holds = abs(p - d) <= claim.rtol * abs(d)
            diff = "" if holds else f"relative difference {abs(p - d) / abs(d):.3g} > {claim.rtol:g}"
        else:
            diff = describe_difference(printed, ours)
            holds = diff == ""
        terms.append(Term(power, printed, ours, holds, diff))
    bad = [t for t in terms if not t.holds]
    text = "; ".join(f"kappa^{t.power}: {t.difference}" for t in bad)
    return tuple(terms), text


def _error_order(claim: Claim, patch: dict, exact: dict) -> tuple[bool, int | None, str]:
    diffs = [k for k in sorted(set(patch) | set(exact))
             if not _same(patch.get(k, 0), exact.get(k, 0))]
    lead = diffs[0] if diffs else None
    m = claim.error_order
    holds = lead is not None and (lead >= m if claim.bound else lead == m) or (
        lead is None and claim.bound)
    shown = f"O(kappa^{lead})" if lead is not None else f"beyond kappa^{claim.order}"
    diff = "" if holds else f"leading error {shown}, claimed O(kappa^{m})"
    return holds, lead, diff


def check_claim(claim: Claim, derived=None, exact=None) -> ClaimResult:
    """Derive ``claim`` (or use the given derivations) and compare; return the verdict.

    ``derived`` is the derived series (or the value of Omega for a value claim), ``exact``
    the exact series for an error-order claim; both default to deriving here.
    """
    tasks = _task(claim)
    if derived is None:
        derived = _run_task(tasks[0])
    if claim.kind == "error_order" and exact is None:
        exact = _run_task(tasks[1])
    terms, p_tex, d_tex = (), "", ""
    if claim.kind == "series":
        terms, diff = _series_verdict(claim, derived)
        holds = all(t.holds for t in terms)
        printed = " + ".join(f"({t.printed})*kappa^{t.power}" for t in terms)
        shown = " + ".join(f"({t.derived})*kappa^{t.power}" for t in terms)
        p_tex = " + ".join(fr"\left({sympy.latex(t.printed)}\right)\kappa^{{{t.power}}}"
                           for t in terms)
        d_tex = " + ".join(fr"\left({sympy.latex(t.derived)}\right)\kappa^{{{t.power}}}"
                           for t in terms)
    elif claim.kind in ("critical_step", "fully_discrete_series"):
        from dispersion.claims import explicit

        holds, printed, shown, diff = explicit.verdict(claim, derived)
    elif claim.kind == "error_order":
        holds, lead, diff = _error_order(claim, derived, exact)
        printed = ("at least " if claim.bound else "") + f"O(kappa^{claim.error_order})"
        shown = f"O(kappa^{lead})" if lead is not None else f"zero to kappa^{claim.order}"
    else:
        ok = derived == derived  # NaN: no such branch
        err = abs(derived - claim.omega) / claim.omega if ok else float("nan")
        holds = ok and err <= claim.rtol
        printed = f"Omega = {claim.omega:.12g} (rtol {claim.rtol:g})"
        shown = f"Omega = {derived:.12g}" if ok else "no such branch there"
        diff = "" if holds else (f"relative difference {err:.3g} > {claim.rtol:g}" if ok
                                 else shown)
    expected = claim.expect == "holds"
    status = {(True, True): "holds", (False, True): "differs",
              (False, False): "differs (expected)", (True, False): "holds (unexpected)"}[
        (holds, expected)]
    if status == "holds (unexpected)":
        diff = "recorded as not holding (expect = 'differs'), but it holds"
    return ClaimResult(claim.name, claim.source, claim.kind, claim.branch, claim.model.label(),
                       claim.file, claim.line, printed, shown, status, holds == expected, diff,
                       terms, p_tex, d_tex, claim.note)


def check_jobs(jobs) -> int:
    """``jobs`` as an int if it is a worker count in [1, :data:`MAX_JOBS`]; raise otherwise.

    >>> check_jobs(100000)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: jobs must be an integer in [1, 64], got 100000
    """
    return check_int_in_range("jobs", jobs, 1, MAX_JOBS)


def verify_claims(claims: list[Claim], *, executor=None, jobs: int | None = None,
                  progress: bool = False) -> Verification:
    """Check every claim; each distinct derivation runs once, independent ones in parallel.

    ``executor``/``jobs`` as in :func:`dispersion.sweep.parallel_map` (``jobs=1``: in this
    process, sharing its cache; default: in-process when every derivation is a series to
    kappa^8 or less, else a process pool; ``jobs`` at most :data:`MAX_JOBS`). A derivation
    that fails marks its claims ``"error"``.
    """
    from dispersion.sweep import parallel_map

    if jobs is not None:
        jobs = check_jobs(jobs)
    start = time.perf_counter()
    tasks = {}
    for claim in claims:
        for t in _task(claim):
            key = t[:3] if t[0] == "series" else t
            if key not in tasks or (t[0] == "series" and t[3] > tasks[key][3]):
                tasks[key] = t
    todo = list(tasks.values())
    if jobs is None and executor is None:
        # series to kappa^8 take ~0.1 s each: a process pool costs more than it saves
        # (paper file, 2 cores: 3.4 s in-process vs 3.9 s with a pool, whole CLI)
        small = all(t[0] == "series" and t[3] <= 8 for t in todo)
        jobs = 1 if small or len(todo) < 3 else None
    done = dict(zip([t[:3] if t[0] == "series" else t for t in todo],
                    parallel_map(_safe_task, todo, executor=executor, jobs=jobs,
                                 progress=progress, desc="claims")))
    results = []
    for claim in claims:
        got = [done[t[:3] if t[0] == "series" else t] for t in _task(claim)]
        failure = next((g for g in got if isinstance(g, str)), None)
        if failure is not None:
            results.append(ClaimResult(claim.name, claim.source, claim.kind, claim.branch,
                                       claim.model.label(), claim.file, claim.line, claim.written,
                                       "", "error", False, failure, note=claim.note))
        else:
            results.append(check_claim(claim, *got))
    files = tuple(dict.fromkeys(c.file for c in claims))
    return Verification(files, tuple(results), time.perf_counter() - start)


def _safe_task(task):
    try:
        return _run_task(task)
    except DispersionError as exc:
        return f"derivation failed: {exc}"


def verify_file(*paths, quick: bool = False, executor=None, jobs: int | None = None
                ) -> Verification:
    """Load every claims file (default: the paper's) and verify all claims together.

    ``quick`` is accepted for the report protocol; claims files define their own work.
    """
    paths = paths or (paper_claims_path(),)
    claims = [c for p in paths for c in load_claims(p)]
    return verify_claims(claims, executor=executor, jobs=jobs)


# --------------------------------------------------------------------------- presenting

def format_results(results, fmt: str = "text", width: int = 60) -> str:
    """Table of results (objects or their JSON dictionaries): ``text`` or ``markdown``."""
    head = ("claim", "source", "printed", "derived", "status", "difference")
    rows = []
    for r in results:
        r = r if isinstance(r, dict) else {f: getattr(r, f) for f in
                                            ("name", "source", "printed", "derived", "status",
                                             "difference")}
        rows.append(tuple(str(r[k] or "") for k in ("name", "source", "printed", "derived",
                                                     "status", "difference")))
    if fmt == "markdown":
        out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
        out += ["| " + " | ".join(c.replace("|", "\\|") for c in row) + " |" for row in rows]
        return "\n".join(out)
    if fmt != "text":
        raise InputError(f"format must be text or markdown, got {fmt!r}")
    cut = lambda s: s if len(s) <= width else s[:width - 3] + "..."
    rows = [tuple(cut(c) if i in (2, 3) else c for i, c in enumerate(row)) for row in rows]
    widths = [max(len(x) for x in col) for col in zip(head, *rows)]
    return "\n".join("  ".join(c.ljust(w) for c, w in zip(row, widths)).rstrip()
                     for row in [head, *rows])


def junit_xml(verification: Verification) -> str:
    """JUnit XML: one test suite per file, one test case per claim (failure = not as expected).

    >>> v = Verification(("f.toml",), (), 0.0)
    >>> junit_xml(v).splitlines()[1]
    '<testsuites name="dispersion verify" tests="0" failures="0" errors="0" time="0.000">'
    """
    res = verification.results
    root = ET.Element("testsuites", {
        "name": "dispersion verify", "tests": str(len(res)),
        "failures": str(sum(not r.passed and r.status != "error" for r in res)),
        "errors": str(sum(r.status == "error" for r in res)),
        "time": f"{verification.seconds:.3f}"})
    for file in verification.files:
        mine = [r for r in res if r.file == file]
        suite = ET.SubElement(root, "testsuite", {
            "name": file, "tests": str(len(mine)),
            "failures": str(sum(not r.passed and r.status != "error" for r in mine)),
            "errors": str(sum(r.status == "error" for r in mine))})
        for r in mine:
            case = ET.SubElement(suite, "testcase", {
                "classname": Path(file).stem, "name": r.name, "file": file, "line": str(r.line)})
            detail = (f"claim: {r.name}\nsource: {r.source or '-'}\nmodel: {r.model}\n"
                      f"printed: {r.printed}\nderived: {r.derived}\nstatus: {r.status}\n"
                      f"difference: {r.difference or '-'}")
            if r.status == "error":
                ET.SubElement(case, "error", {"message": r.difference}).text = detail
            elif not r.passed:
                ET.SubElement(case, "failure", {"message": f"{r.status}: {r.difference}"}
                              ).text = detail
            else:
                ET.SubElement(case, "system-out").text = detail
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, "unicode") + "\n"
