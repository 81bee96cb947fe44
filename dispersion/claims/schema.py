"""Claims files read into values: TOML -> :class:`Claim` / :class:`Model`, every field checked.

A claims file is untrusted text. It is refused with one :class:`~dispersion.errors.InputError`
naming file, line, entry and field unless it is a regular UTF-8 file of at most
:data:`MAX_FILE_BYTES`, nested at most :data:`MAX_NESTING` tables deep, and every field has
its type and range. Expressions and numbers go through :mod:`dispersion.claims.reader`
(a whitelist, never evaluated); the derivation a claim asks for is bounded here by the
toolkit's own limits (:func:`dispersion.symbolic.power_balance.check_request`,
:func:`dispersion.symbolic.plate.check_size`) before any work starts.
"""
from __future__ import annotations

import math
import os
import re
import stat
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import sympy

from dispersion import defaults
from dispersion.claims import reader
from dispersion.claims.report import readable
from dispersion.errors import InputError
from dispersion.symbolic.power_balance import BRANCHES, NU, R_SYM

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ["EXACT", "KINDS", "KAPPA", "PATCH_KEYS", "KIND_FIELDS", "CLAIM_KEYS",
           "MAX_FILE_BYTES",
           "MAX_NESTING", "MAX_INT_BITS", "Model", "Claim", "paper_claims_path", "load_claims",
           "parse_claims"]

#: Name of the exact model (the Rayleigh-Lamb equation of :mod:`dispersion.waves.rayleigh_lamb`).
EXACT = "rayleigh-lamb"
KINDS = ("series", "error_order", "value", "critical_step", "fully_discrete_series")
KAPPA = sympy.Symbol("kappa")
PATCH_KEYS = ("p", "n", "r", "mass", "contact", "gamma_s", "weights")
#: The keys that belong to one kind of claim only (a claim of another kind refuses them).
KIND_FIELDS = {"series": ("syntax", "coefficients", "series", "nu", "rtol"),
               "error_order": ("error_order", "bound"),
               "value": ("kappa", "nu", "omega", "rtol"),
               # explicit dynamics (dispersion.claims.explicit)
               "critical_step": ("ratio", "omega_max", "nu", "rtol"),
               "fully_discrete_series": ("coefficients", "scheme", "nu", "syntax")}
_KIND_KEYS = {key for keys in KIND_FIELDS.values() for key in keys}
CLAIM_KEYS = {"name", "source", "note", "kind", "branch", "model", *PATCH_KEYS, "expect",
              *_KIND_KEYS}
TOP_KEYS = ("title", "format", "defaults", "claim")
#: The kinds read by :mod:`dispersion.claims.explicit` (critical time step, fully discrete).
EXPLICIT_KINDS = ("critical_step", "fully_discrete_series")
#: Largest claims file read. The paper's file has 4 KiB; a manuscript with a thousand claims
#: stays under 1 MiB, and TOML parsing of 1 MiB takes well under a second.
MAX_FILE_BYTES = 2**20
#: Deepest nesting of tables and arrays: ``[[claim]]`` -> ``weights`` -> contact -> neighbour.
MAX_NESTING = 6
#: Largest TOML integer taken as a number (about 60 digits, as :data:`reader.MAX_DIGITS`).
MAX_INT_BITS = 200
#: Value claims: the largest kappa and Omega (the exact tracer scans Omega up to 2 Omega + 1;
#: the CLI's ``branches --omega-max`` stops at 200 for the same reason).
MAX_VALUE = 200.0


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
    """One claim of a claims file (see :mod:`dispersion.claims` for its fields)."""

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


# --------------------------------------------------------------------------- files

def paper_claims_path() -> Path:
    """The claims file of the paper's eqs (14)-(20) shipped with the package."""
    from importlib import resources

    return Path(str(resources.files("dispersion") / "data" / "paper_claims.toml"))


def read_text(path) -> str:
    """The text of a claims file, refused unless a regular UTF-8 file of bounded size.

    Opened without blocking (a fifo does not hang) and checked on the open descriptor, so
    ``/dev/zero`` or a named pipe is refused before a byte is read.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise InputError(f"claims file must be a path, got {type(path).__name__}")
    path = Path(path)
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0))
    except (OSError, ValueError) as exc:  # ValueError: a NUL byte in the name
        raise InputError(f"{path}: cannot read claims file "
                         f"({getattr(exc, 'strerror', None) or exc})") from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise InputError(f"{path}: not a regular file (a claims file is TOML text)")
        if info.st_size > MAX_FILE_BYTES:
            raise InputError(f"{path}: claims file of {info.st_size} bytes, more than the limit "
                             f"of {MAX_FILE_BYTES} bytes")
        with os.fdopen(fd, "rb", closefd=False) as handle:
            data = handle.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise InputError(f"{path}: cannot read claims file ({exc.strerror or exc})") from None
    finally:
        os.close(fd)
    if len(data) > MAX_FILE_BYTES:  # grew while we read it
        raise InputError(f"{path}: claims file larger than the limit of {MAX_FILE_BYTES} bytes")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"{path}: not UTF-8 text (byte 0x{data[exc.start]:02x} at offset "
                         f"{exc.start})") from None


def load_claims(path) -> list[Claim]:
    """Read and check a claims file; raise :class:`InputError` naming file, line, entry, field."""
    return parse_claims(read_text(path), str(path))


def _depth(data) -> int:
    """Nesting depth of parsed TOML (tables and arrays), counted without recursion."""
    deepest, stack = 0, [(data, 0)]
    while stack:
        node, level = stack.pop()
        if isinstance(node, (dict, list)):
            deepest = max(deepest, level)
            if level <= MAX_NESTING:
                stack += [(x, level + 1) for x in (node.values() if isinstance(node, dict)
                                                  else node)]
    return deepest


def parse_claims(text: str, file: str = "<string>") -> list[Claim]:
    """Parse the TOML text of a claims file (see :mod:`dispersion.claims`)."""
    if not isinstance(text, str):
        raise InputError(f"claims text must be a string (TOML), got {type(text).__name__}")
    if not isinstance(file, str):
        raise InputError(f"file must be a string naming the claims file, got "
                         f"{type(file).__name__}")
    if len(text) > MAX_FILE_BYTES:
        raise InputError(f"{file}: claims text of {len(text)} characters, more than the limit "
                         f"of {MAX_FILE_BYTES}")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{file}: malformed TOML: {exc}") from None
    except RecursionError:
        raise InputError(f"{file}: malformed TOML: nested more than {MAX_NESTING} levels "
                         "deep") from None
    except ValueError as exc:  # e.g. an integer of more than 4300 digits
        raise InputError(f"{file}: malformed TOML: {str(exc)[:200]}") from None
    if _depth(data) > MAX_NESTING:
        raise InputError(f"{file}: tables and arrays nested more than {MAX_NESTING} levels deep")
    lines = _Lines(text, file)
    unknown = set(data) - set(TOP_KEYS)
    if unknown:
        key = sorted(unknown)[0]
        raise InputError(f"{lines.top(key)}: unknown key {_shown(key)} (allowed: "
                         f"{', '.join(TOP_KEYS)})")
    if "title" in data and not isinstance(data["title"], str):
        raise InputError(f"{lines.top('title')}: title must be a string, got "
                         f"{_shown(data['title'])}")
    if "format" in data and (type(data["format"]) is not int or data["format"] != 1):
        raise InputError(f"{lines.top('format')}: format must be 1, got "
                         f"{_shown(data['format'])}")
    base = data.get("defaults", {})
    if not isinstance(base, dict) or "name" in base or set(base) - CLAIM_KEYS:
        bad = "name" if isinstance(base, dict) and "name" in base else (
            sorted(set(base) - CLAIM_KEYS)[0] if isinstance(base, dict) else "defaults")
        raise InputError(f"{lines.top('defaults')}: [defaults] may hold claim keys except "
                         f"name (field {_shown(bad)})")
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


def _shown(value, limit: int = 60) -> str:
    """``repr`` of a user's value for a message: control characters escaped, length bounded."""
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 200:
        return f"an integer of {value.bit_length()} bits"
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


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
        hit = self._find(key[:100], lo, hi) if key else None
        return (hit if hit is not None else lo) + 1

    def at(self, i: int, key: str | None = None) -> str:
        return f"{self.file}:{self.line(i, key)}"


# --------------------------------------------------------------------------- fields

def _claim(entry: dict, own: dict, i: int, lines: _Lines) -> Claim:
    name = own.get("name")
    where = lines.at(i)
    if not isinstance(name, str) or not name.strip():
        raise InputError(f"{where}: claim #{i + 1}: field 'name': required (a non-empty string)")

    def fail(key, message):
        line = lines.line(i, key)
        if key.isdigit() and line == lines.line(i):  # a power inside an inline table
            line = lines.line(i, "coefficients")
        raise InputError(f"{lines.file}:{line}: claim {name!r}: field {_shown(key)}: {message}")

    unknown = sorted(set(entry) - CLAIM_KEYS)
    if unknown:
        fail(unknown[0], f"unknown key (allowed: {', '.join(sorted(CLAIM_KEYS))})")
    for key in ("kind", "branch", "model", "expect", "syntax", "source", "note", "mass",
                "contact", "series"):
        if key in entry and not isinstance(entry[key], str):
            fail(key, f"must be a string, got {_shown(entry[key])}")
    kind = entry.get("kind", "series")
    if kind not in KINDS:
        fail("kind", f"must be one of {', '.join(KINDS)}, got {_shown(kind)}")
    if kind in EXPLICIT_KINDS:
        return _explicit_claim(entry, own, name, kind, lines.file, lines.line(i), fail)
    branch = entry.get("branch")
    ok = (re.fullmatch(r"[SA]\d{1,3}", branch or "") if kind == "value" else branch in BRANCHES)
    if not isinstance(branch, str) or not ok:
        fail("branch", "must be S0 or A0" + (" (or S1, A1, ...)" if kind == "value" else "")
             + f", got {_shown(branch)}")
    model = _model(entry, own, fail)
    expect = entry.get("expect", "holds")
    if expect not in ("holds", "differs"):
        fail("expect", f"must be 'holds' or 'differs', got {_shown(expect)}")
    common = dict(name=name, kind=kind, branch=branch, model=model, file=lines.file,
                  line=lines.line(i), source=entry.get("source"), note=entry.get("note"),
                  expect=expect)
    for key in sorted(_KIND_KEYS - set(KIND_FIELDS[kind])):
        if key in own:
            fail(key, f"not a field of a {kind} claim")
    claim = KIND_PARSERS[kind](entry, common, fail)
    _check_patch(model, entry, fail)
    return claim


def _explicit_claim(entry, own, name, kind, file, line, fail) -> Claim:
    """A claim of :mod:`dispersion.claims.explicit`, read with this module's model builder
    and expression reader (one reader, one model builder)."""
    from dispersion.claims import explicit

    expect = entry.get("expect", "holds")
    if expect not in ("holds", "differs"):
        fail("expect", f"must be 'holds' or 'differs', got {_shown(expect)}")
    common = dict(name=name, kind=kind, branch=str(entry.get("branch", "-"))[:20], model=None,
                  file=file, line=line, source=entry.get("source"), note=entry.get("note"),
                  expect=expect)
    claim = explicit.parse(entry, own, common, fail, _model, _expression)
    if claim.model.name != "bar":
        _check_patch(claim.model, entry, fail)
    return claim


def _error_order_claim(entry: dict, common: dict, fail) -> Claim:
    if common["model"].exact:
        fail("model", "an error order compares a patch with the exact model: give a patch")
    m = entry.get("error_order")
    if type(m) is not int or m < 2 or m % 2:
        fail("error_order", f"must be an even integer >= 2, got {_shown(m)}")
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
        check_request(claim.branch, claim.order, exact=claim.model.exact,
                      n=None if claim.model.exact else claim.model.n)
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
        q = _value(entry[key], key, fail)
        values[key] = float(q) if abs(q) < 10**300 else math.inf
    if not (-1 < values["nu"] < 0.5):
        fail("nu", f"must lie in (-1, 0.5), got {values['nu']}")
    for key in ("kappa", "omega"):
        if not 0 <= values[key] <= MAX_VALUE or (key == "omega" and values[key] == 0):
            fail(key, f"must lie in {'[0' if key == 'kappa' else '(0'}, {MAX_VALUE:g}], "
                      f"got {values[key]:g}")
    if not 0 < values["rtol"] < 1:
        fail("rtol", f"must lie in (0, 1), got {values['rtol']:g}")
    if not model.exact and model.name == "bloch" and model.r == R_SYM:
        fail("r", "a value claim needs a number for the aspect ratio r")
    return Claim(**common, written=f"Omega({values['kappa']:g}) = {values['omega']:.12g}",
                 **values)


def _value(value, key, fail, symbol=None):
    """An exact number of a value field: a TOML integer, float or string (``"1/2"``).

    Strings go through :func:`dispersion.claims.reader.read_number` (bounded digits, no
    evaluation); floats through their shortest decimal text (0.3 is 3/10); NaN, infinities,
    booleans and integers of more than :data:`MAX_INT_BITS` bits are refused.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        fail(key, f"must be a number (or a fraction such as '1/2'), got {_shown(value)}")
    if isinstance(value, int):
        if value.bit_length() > MAX_INT_BITS:
            fail(key, f"an integer of {value.bit_length()} bits is out of range (at most "
                      f"{MAX_INT_BITS} bits)")
        return Fraction(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            fail(key, f"must be a finite number, got {value!r}")
        value = repr(value)
    elif symbol is not None and value.strip() == str(symbol):
        return symbol
    try:
        return reader.read_number(value)
    except InputError as exc:
        fail(key, f"{_shown(value)} is not a number: {exc}")


def _rational(value, key, fail, symbol=None):
    q = _value(value, key, fail, symbol)
    return q if q is symbol else sympy.Rational(q.numerator, q.denominator)


def _model(entry: dict, own: dict, fail) -> Model:
    name = entry.get("model", defaults.MODEL)
    if name == EXACT:  # patch keys inherited from [defaults] do not apply to it
        given = [k for k in PATCH_KEYS if k in own]
        if given:
            fail(given[0], "not a setting of the exact model (rayleigh-lamb)")
        return Model(EXACT)
    from dispersion.symbolic.plate import MODELS, check_size

    if name not in MODELS:
        fail("model", f"must be {EXACT!r} or a patch model ({', '.join(MODELS)}), "
                      f"got {_shown(name)}")
    kw = {}
    for key in ("p", "n"):
        if key in entry:
            if type(entry[key]) is not int:
                fail(key, f"must be an integer, got {_shown(entry[key])}")
            kw[key] = entry[key]
    for key in ("mass", "contact"):
        if key in entry:
            kw[key] = entry[key]
    if "r" in entry:
        kw["r"] = _rational(entry["r"], "r", fail, symbol=R_SYM)
    if "gamma_s" in entry:
        kw["gamma_s"] = _rational(entry["gamma_s"], "gamma_s", fail)
    if "weights" in entry:
        kw["weights"] = _weights(entry["weights"], fail)
    model = Model(name, **kw)
    if name != "bloch" and "r" in entry:
        fail("r", f"the aspect ratio belongs to the bloch model, not {name!r}")
    try:
        check_size(model.p, model.n)
        from dispersion.symbolic.power_balance import MAX_WORK

        if (2 * model.n) ** 2 * 2 > MAX_WORK:  # the least work of any series claim
            raise InputError(f"control points n must satisfy (2n)^2 * order <= {MAX_WORK} "
                             f"(bounded time and memory), got n = {model.n}")
    except InputError as exc:
        _patch_failure(exc, entry, fail)
    return model


def _patch_failure(exc: InputError, entry: dict, fail) -> None:
    words = str(exc).split(" must")[0].replace("(", " ").split()
    key = next((k for k in PATCH_KEYS if k in words and k in entry), "model")
    fail(key, f"the toolkit cannot build this patch: {exc}")


def _check_patch(model: Model, entry: dict, fail) -> None:
    """Build the patch once (after the work is known to be bounded): every setting checked."""
    if model.exact:
        return
    from dispersion.symbolic.plate import plate_patch

    try:
        plate_patch(**model.patch_kwargs())
    except InputError as exc:
        _patch_failure(exc, entry, fail)


def _weights(w, fail) -> tuple:
    """``{contact index: {neighbour index: weight}}`` as a sorted tuple of tuples."""
    if not isinstance(w, dict) or not w or len(w) > 64:
        fail("weights", "must be a table {contact index: {neighbour index: weight}} "
                        "(at most 64 contact indices)")
    out = []
    for c, ws in w.items():
        if not re.fullmatch(r"0|[1-9]\d{0,2}", c) or not isinstance(ws, dict) or not ws \
                or len(ws) > 64:
            fail("weights", f"must be a table {{contact index: {{neighbour index: weight}}}}, "
                            f"got key {_shown(c)}")
        row = []
        for j, v in ws.items():
            if not re.fullmatch(r"0|[1-9]\d{0,2}", j):
                fail("weights", f"neighbour index must be a whole number < 1000, got {_shown(j)}")
            row.append((int(j), _rational(v, "weights", fail)))
        out.append((int(c), tuple(sorted(row))))
    return tuple(sorted(out))


def _expression(text, key, syntax, fail):
    """A coefficient or series: text through the reader; a TOML number as an exact value."""
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return _rational(text, key, fail)
    if not isinstance(text, str) or not text.strip():
        fail(key, f"must be an expression (a string), got {_shown(text)}")
    try:
        return reader.read(text, syntax)
    except InputError as exc:
        what = "LaTeX" if syntax == "latex" else "sympy text"
        fail(key, f"{exc} (reading {what} {_shown(text)})")


def _series_claim(entry: dict, common: dict, fail) -> Claim:
    syntax = entry.get("syntax", "sympy")
    if syntax not in reader.SYNTAXES:
        fail("syntax", f"must be 'sympy' or 'latex', got {_shown(syntax)}")
    has_c, has_s = "coefficients" in entry, "series" in entry
    if has_c == has_s:
        fail("coefficients", "give either a coefficients table or a series expression")
    branch = common["branch"]
    sigma = BRANCHES[branch][1]
    exact = common["model"].exact
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
                fail(k, f"{rule}, written without leading zeros; got {_shown(k)}")
            expr = _expression(text, k, syntax, fail)
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
            fail("series", f"{exc} (reading {what} {_shown(text)})")
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
        nu = _rational(nu, "nu", fail)
        if not (-1 < nu < sympy.Rational(1, 2)):
            fail("nu", f"must lie in (-1, 0.5), got {nu}")
        printed = {k: v.subs(NU, nu) for k, v in printed.items()}
    rtol = entry.get("rtol")
    if rtol is not None:
        if nu is None:
            fail("rtol", "a tolerance on series coefficients needs a number for nu")
        q = _value(rtol, "rtol", fail)
        if not 0 < q < 1:
            fail("rtol", f"must lie in (0, 1), got {_shown(rtol)}")
        rtol = float(q)
    allowed = {NU, R_SYM} if common["model"].r == R_SYM else {NU}
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
                "value": _value_claim}
