"""Claims checked: the derivations a claim needs, their scheduling, and the verdicts.

Each kind of claim is one entry of :data:`KIND_RULES`: the derivations it needs
(``tasks``) and how it compares them with what was printed (``verdict``, which returns the
:class:`ClaimResult` through :func:`verdict`). A new kind adds its parsing in
:mod:`dispersion.claims.schema` (``KINDS``, ``KIND_FIELDS``, ``KIND_PARSERS``; the
explicit-dynamics kinds in :mod:`dispersion.claims.explicit`) and one entry here.
"""
from __future__ import annotations

import functools
import time
from dataclasses import dataclass, field
from typing import Callable

import sympy

from dispersion.claims import explicit, orders
from dispersion.claims.claim import Claim
from dispersion.claims.claim_model import ClaimModel
from dispersion.claims.claims_file import paper_claims_path
from dispersion.claims.exact_model import ExactModel
from dispersion.claims.limits import MAX_JOBS
from dispersion.claims.report import readable
from dispersion.claims.schema import load_claims
from dispersion.errors import DispersionError, InputError, check_int_in_range
from dispersion.rendering import Rendered
from dispersion.symbolic.power_balance import NU

__all__ = ["MAX_JOBS", "MAX_DERIVATIONS", "Term", "ClaimResult", "Verification", "KIND_RULES",
           "verdict", "describe_difference", "check_claim", "check_jobs", "verify_claims",
           "verify_file"]

#: Most distinct derivations one verification runs. Each is bounded by the engine's own
#: limits (about a minute at worst, :func:`dispersion.symbolic.power_balance.check_request`);
#: the paper's file needs 8 and a series to kappa^8 takes ~0.1 s, so 100 cheap ones take
#: seconds, and a file cannot ask for more than 100 dear ones.
MAX_DERIVATIONS = 100


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


@dataclass(frozen=True, repr=False)  # Rendered: short repr; text, CSV, JSON from the rows
class Verification(Rendered):
    """Every claim of one or more files, checked; ``passed`` if each holds as expected.

    Renders itself (:class:`dispersion.rendering.Rendered`): one row per claim; the claims
    that do not hold as recorded are its ``failures``; text and Markdown are those of
    :func:`dispersion.claims.report.format_results`, with the count of claims that hold.
    """

    files: tuple[str, ...]
    results: tuple[ClaimResult, ...]
    seconds: float
    passed: bool = field(init=False)

    def __post_init__(self):
        object.__setattr__(self, "passed", all(r.passed for r in self.results))

    def title(self) -> str:
        held = sum(r.passed for r in self.results)
        return f"{held} of {len(self.results)} claims hold as recorded"

    def header_lines(self) -> list[str]:
        return [f"claims file: {f}" for f in dict.fromkeys(self.files)]

    def columns(self) -> tuple[str, ...]:
        return ("claim", "source", "kind", "branch", "model", "printed", "derived", "status",
                "difference", "file", "line")

    def rows(self) -> list[dict]:
        return [{"claim": r.name, "source": r.source or "", "kind": r.kind, "branch": r.branch,
                 "model": r.model, "printed": r.printed, "derived": r.derived,
                 "status": r.status, "difference": r.difference, "file": r.file,
                 "line": r.line} for r in self.results]

    @property
    def failures(self) -> tuple[str, ...]:
        return tuple(f"claim {r.name!r} ({r.file}:{r.line}) {r.status}"
                     + (f": {r.difference}" if r.difference else "")
                     for r in self.results if not r.passed)

    def to_text(self, digits: int = 7) -> str:
        from dispersion.claims.report import format_results, plain

        failed = [r for r in self.results if not r.passed]
        summary = self.title() + (": not " + ", ".join(repr(r.name) for r in failed)
                                  if failed else "")
        return format_results(self.results, "text") + "\n" + plain(summary)

    def to_markdown(self, digits: int = 7) -> str:
        from dispersion.claims.report import format_results, plain

        return format_results(self.results, "markdown") + "\n\n" + plain(self.title())


# --------------------------------------------------------------------------- deriving

@functools.lru_cache(maxsize=64)
def _series(model: ClaimModel, branch: str, order: int) -> dict[int, sympy.Expr]:
    """Derived series of ``branch`` of ``model`` to kappa^order (cached per process)."""
    if isinstance(model, ExactModel):
        from dispersion.continuum.exact_series import exact_series

        return exact_series(branch, order)
    from dispersion.symbolic.power_balance import discrete_series

    return discrete_series(branch, order, model, nu=model.nu)


def _omega(model: ClaimModel, branch: str, kappa: float, nu: float, guess: float) -> float:
    """Omega of ``branch`` at one kappa (NaN if it does not exist below 2 guess + 1)."""
    if isinstance(model, ExactModel):
        from dispersion.continuum.exact_branches import trace_branches

        br = trace_branches(nu, [kappa], 2 * guess + 1)
    else:
        from dispersion.symbolic.plate import plate_patch
        from dispersion.discretization.discrete_branches import discrete_branches

        br = discrete_branches(plate_patch(model), nu, [kappa])
    return float(br.omega[branch][0]) if branch in br.omega else float("nan")


def _key(task: tuple) -> tuple:
    """Tasks with equal keys share one derivation: a series to the highest order asked."""
    return task[:3] if task[0] == "series" else task


def _run_task(task: tuple):
    if task[0] in explicit.KINDS:
        return explicit.run(task)
    if task[0] in orders.KINDS:
        return orders.run(task)
    if task[0] == "series":
        return _series(*task[1:])
    if task[0] == "value":
        return _omega(*task[1:])
    raise InputError(f"unknown derivation {task[0]!r}")


def _safe_task(task):
    try:
        return _run_task(task)
    except DispersionError as exc:
        return f"derivation failed: {exc}"


# --------------------------------------------------------------------------- verdicts

def _same(a, b) -> bool:
    return sympy.cancel(sympy.together(a - b)) == 0


def _show(expr) -> str:
    """``1 - nu`` rather than sympy's ``-nu + 1``."""
    const, rest = sympy.expand(expr).as_coeff_Add()
    return f"{const} - {-rest}" if const and rest.could_extract_minus_sign() else str(expr)


def _numer_terms(expr, gens: list) -> dict | None:
    """Monomials of a polynomial numerator in ``gens`` (None if it is not one: sqrt(nu))."""
    if not gens:
        return {(): expr}
    try:
        return dict(sympy.Poly(expr, *gens).terms())
    except sympy.PolynomialError:
        return None


def _expr(value, name: str):
    """A sympy value of :func:`describe_difference`; text is refused, never sympified."""
    if isinstance(value, str):
        raise InputError(f"{name} must be a sympy expression or a number, not text (read text "
                         "with dispersion.claims.reader.read)")
    from dispersion.reader import as_sympy

    return as_sympy(name, value)  # numbers and sympy objects only: no container of text


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
    printed, derived = _expr(printed, "printed"), _expr(derived, "derived")
    diff = sympy.cancel(printed - derived)
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
        syms = sorted(sympy.expand(pn).free_symbols | sympy.expand(dn).free_symbols, key=str)
        a, b = _numer_terms(sympy.expand(pn), syms), _numer_terms(sympy.expand(dn), syms)
        changed = ([m for m in set(a) | set(b) if a.get(m, 0) != b.get(m, 0)]
                   if a is not None and b is not None else [])
        if len(changed) == 1:
            m = changed[0]
            mono = sympy.Mul(*[s**e for s, e in zip(syms, m)])
            was, now = b.get(m, 0) * mono, a.get(m, 0) * mono
            return f"numerator term {was} -> {now} (same denominator {_show(readable(pd))})"
        return (f"numerator: printed {readable(pn)}, derived {readable(dn)} "
                f"(same denominator {readable(dd)})")
    k = sympy.cancel(pn / dn)
    if k.is_number:  # same numerator up to a constant: the denominators differ
        pd, dd = sympy.expand(pd / k), sympy.expand(dd)
        if dd.as_coeff_Add()[0] < 0:
            pd, dd = -pd, -dd
        return f"denominator: printed {_show(readable(pd))}, derived {_show(readable(dd))}"
    return f"difference printed - derived = {readable(diff)}"


def verdict(claim: Claim, holds: bool, printed: str, derived: str, difference: str,
            terms: tuple[Term, ...] = (), printed_latex: str = "", derived_latex: str = "",
            *, error: bool = False) -> ClaimResult:
    """The result of ``claim`` from what its comparison found (``holds`` and the texts shown);
    ``status`` and ``passed`` follow from ``holds`` and what the claim expects, or ``error``
    (a derivation or a comparison that failed, ``difference`` says which)."""
    expected = claim.expect == "holds"
    if error:
        status = "error"
    else:
        status = {(True, True): "holds", (False, True): "differs",
                  (False, False): "differs (expected)", (True, False): "holds (unexpected)"}[
            (holds, expected)]
        if status == "holds (unexpected)":
            difference = "recorded as not holding (expect = 'differs'), but it holds"
    return ClaimResult(claim.name, claim.source, claim.kind, claim.branch, claim.model.label(),
                       claim.file, claim.line, printed, derived, status,
                       not error and holds == expected, difference, tuple(terms),
                       printed_latex, derived_latex, claim.note)


def _series_tasks(claim: Claim) -> list[tuple]:
    return [("series", claim.model, claim.branch, claim.order)]


def _series_verdict(claim: Claim, derived: dict) -> ClaimResult:
    terms = []
    for power, printed in claim.printed:
        ours = derived.get(power, sympy.Integer(0))
        if claim.nu is not None:
            ours = sympy.factor(ours.subs(NU, claim.nu))
        if claim.rtol is not None:
            p, d = float(printed), float(ours)
            holds = abs(p - d) <= claim.rtol * abs(d)
            diff = "" if holds else (f"relative difference {abs(p - d) / abs(d):.3g} > "
                                     f"{claim.rtol:g}" if d else f"printed {p:g}, derived 0")
        else:
            diff = describe_difference(printed, ours)
            holds = diff == ""
        terms.append(Term(power, printed, ours, holds, diff))
    text = "; ".join(f"kappa^{t.power}: {t.difference}" for t in terms if not t.holds)
    return verdict(
        claim, all(t.holds for t in terms),
        " + ".join(f"({t.printed})*kappa^{t.power}" for t in terms),
        " + ".join(f"({t.derived})*kappa^{t.power}" for t in terms),
        text, tuple(terms),
        " + ".join(fr"\left({sympy.latex(t.printed)}\right)\kappa^{{{t.power}}}" for t in terms),
        " + ".join(fr"\left({sympy.latex(t.derived)}\right)\kappa^{{{t.power}}}" for t in terms))


def _error_order_tasks(claim: Claim) -> list[tuple]:
    return [("series", claim.model, claim.branch, claim.order),
            ("series", ExactModel(), claim.branch, claim.order)]


def _error_order_verdict(claim: Claim, patch: dict, exact: dict) -> ClaimResult:
    from dispersion.symbolic.power_balance import first_difference

    lead = first_difference(patch, exact, upto=claim.order)
    m = claim.error_order
    holds = lead is not None and (lead >= m if claim.bound else lead == m) or (
        lead is None and claim.bound)
    shown = f"O(kappa^{lead})" if lead is not None else f"beyond kappa^{claim.order}"
    return verdict(claim, holds, ("at least " if claim.bound else "") + f"O(kappa^{m})",
                   f"O(kappa^{lead})" if lead is not None else f"zero to kappa^{claim.order}",
                   "" if holds else f"leading error {shown}, claimed O(kappa^{m})")


def _value_tasks(claim: Claim) -> list[tuple]:
    return [("value", claim.model, claim.branch, claim.kappa, claim.nu, claim.omega)]


def _value_verdict(claim: Claim, derived: float) -> ClaimResult:
    ok = derived == derived  # NaN: no such branch
    err = abs(derived - claim.omega) / claim.omega if ok else float("nan")
    holds = ok and err <= claim.rtol
    shown = f"Omega = {derived:.12g}" if ok else "no such branch there"
    return verdict(claim, holds, f"Omega = {claim.omega:.12g} (rtol {claim.rtol:g})", shown,
                   "" if holds else (f"relative difference {err:.3g} > {claim.rtol:g}" if ok
                                     else shown))


@dataclass(frozen=True)
class KindRule:
    """How one kind of claim is checked: its derivations and its comparison."""

    tasks: Callable[[Claim], list[tuple]]
    verdict: Callable[..., ClaimResult]


def _explicit_tasks(claim: Claim) -> list[tuple]:
    return [explicit.task(claim)]


def _explicit_verdict(claim: Claim, derived) -> ClaimResult:
    return verdict(claim, *explicit.verdict(claim, derived))


#: One entry per kind of claim (the keys are :data:`dispersion.claims.schema.KINDS`).
KIND_RULES = {
    "series": KindRule(_series_tasks, _series_verdict),
    "error_order": KindRule(_error_order_tasks, _error_order_verdict),
    "value": KindRule(_value_tasks, _value_verdict),
    "critical_step": KindRule(_explicit_tasks, _explicit_verdict),
    "fully_discrete_series": KindRule(_explicit_tasks, _explicit_verdict),
    "order_range": KindRule(lambda c: [orders.task(c)],
                            lambda c, d: verdict(c, *orders.verdict(c, d))),
}


def _task(claim: Claim) -> list[tuple]:
    """The derivations a claim needs (shared between claims with equal tasks)."""
    return KIND_RULES[claim.kind].tasks(claim)


def _check_claim_value(claim) -> Claim:
    if not isinstance(claim, Claim):
        raise InputError(f"a claim must be a dispersion.claims.Claim (from parse_claims or "
                         f"load_claims), got {type(claim).__name__}")
    if claim.kind not in KIND_RULES:
        raise InputError(f"claim {claim.name!r}: kind must be one of "
                         f"{', '.join(KIND_RULES)}, got {claim.kind!r}")
    return claim


def check_claim(claim: Claim, *derived) -> ClaimResult:
    """Derive ``claim`` (or use the given derivations) and compare; return the verdict.

    ``derived`` are the results of the claim's derivations in order (a series, or the value of
    Omega for a value claim, then the exact series for an error-order claim); by default
    they are derived here.
    """
    claim = _check_claim_value(claim)
    tasks = _task(claim)
    got = list(derived) + [None] * (len(tasks) - len(derived))
    got = [_run_task(t) if g is None else g for t, g in zip(tasks, got)]
    return KIND_RULES[claim.kind].verdict(claim, *got)


# --------------------------------------------------------------------------- scheduling

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

    if not isinstance(claims, (list, tuple)):
        raise InputError(f"claims must be a list of claims (from parse_claims or load_claims), "
                         f"got {type(claims).__name__}")
    claims = [_check_claim_value(c) for c in claims]
    if jobs is not None:
        jobs = check_jobs(jobs)
    start = time.perf_counter()
    tasks = {}
    for claim in claims:
        for t in _task(claim):
            key = _key(t)
            if key not in tasks or (t[0] == "series" and t[3] > tasks[key][3]):
                tasks[key] = t
    todo = list(tasks.values())
    if len(todo) > MAX_DERIVATIONS:
        raise InputError(f"the claims need {len(todo)} distinct derivations, more than the "
                         f"limit of {MAX_DERIVATIONS} per verification (split the files)")
    if jobs is None and executor is None:
        # series to kappa^8 take ~0.1 s each: a process pool costs more than it saves
        # (paper file, 2 cores: 3.4 s in-process vs 3.9 s with a pool, whole CLI)
        small = all(t[0] == "series" and t[3] <= 8 for t in todo)
        jobs = 1 if small or len(todo) < 3 else None
    done = dict(zip([_key(t) for t in todo],
                    parallel_map(_safe_task, todo, executor=executor, jobs=jobs,
                                 progress=progress, desc="claims")))
    results = []
    for claim in claims:
        got = [done[_key(t)] for t in _task(claim)]
        failure = next((g for g in got if isinstance(g, str)), None)
        if failure is not None:
            results.append(verdict(claim, False, claim.written, "", failure, error=True))
        else:
            results.append(_checked(claim, got))
    files = tuple(dict.fromkeys(c.file for c in claims))
    return Verification(files, tuple(results), time.perf_counter() - start)


def _checked(claim: Claim, got: list) -> ClaimResult:
    """The verdict, or an ``error`` result naming what failed: one claim's printed text
    (written by a stranger) must not stop the verification of the others."""
    try:
        return check_claim(claim, *got)
    except Exception as exc:  # noqa: BLE001 - reported per claim, the run goes on
        return verdict(claim, False, claim.written, "", f"the comparison failed: "
                       f"{type(exc).__name__}: {str(exc)[:200]}", error=True)


def verify_file(*paths, quick: bool = False, executor=None, jobs: int | None = None
                ) -> Verification:
    """Load every claims file (default: the paper's) and verify all claims together.

    ``quick`` is accepted for the report protocol; claims files define their own work.
    """
    paths = paths or (paper_claims_path(),)
    claims = [c for p in paths for c in load_claims(p)]
    return verify_claims(claims, executor=executor, jobs=jobs)
