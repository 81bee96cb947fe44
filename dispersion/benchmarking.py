"""Series benchmark: our power-balance engine against Maxima and the textbook sympy route.

Three routes derive the same long-wave coefficients :math:`\\Omega^2 = \\sum_j a_j \\kappa^{2j}`:

* **ours**: :func:`dispersion.power_balance.discrete_series` / :func:`~dispersion.power_balance.exact_series`
  (truncated sparse polynomials over QQ, order-by-order solve in QQ(nu));
* **maxima**: ``benchmarks/maxima/rayleigh_lamb_series.mac`` (Rayleigh-Lamb only, ``taylor``
  arithmetic), run as a subprocess and timed by wall clock, start-up included;
* **textbook**: sympy ``Matrix.det`` of the full :math:`6 \\times 6` :math:`K_{dyn}` (or the
  Rayleigh-Lamb function with sympy ``cos``/``sin``), then :math:`\\Omega^2 = \\sum_j a_j
  \\kappa^{2j}` substituted, ``series`` in :math:`\\kappa` and ``solve`` order by order.

The textbook route runs in a child process under a time budget: the orders it finished in time
are kept, the rest are reported as "> budget". Every coefficient two routes both computed is
compared exactly (``cancel(a - b) == 0``).

>>> coeffs, seconds = parse_maxima_output("COEF S0 2 -2/(nu-1)\\nTIME 0.01\\n")
>>> coeffs["S0"][2], seconds
(-2/(nu - 1), 0.01)

References
----------
A. Tkachuk et al., eqs (14)-(20). Maxima, a computer algebra system, https://maxima.sourceforge.io
(``taylor``). F. A. Amirkulova, PhD thesis, Rutgers 2011 (power balance).
"""
from __future__ import annotations

import multiprocessing
import os
import queue as _queue
import re
import resource
import shutil
import subprocess
import time
from collections.abc import Callable, Iterator
from dataclasses import asdict, dataclass, field
from pathlib import Path

import sympy

from .errors import InputError, check_positive, check_positive_int

__all__ = [
    "NU",
    "BenchmarkResult",
    "RouteResult",
    "Row",
    "compare",
    "format_table",
    "maxima_script",
    "order_sweep",
    "parse_maxima_output",
    "run_benchmark",
    "run_maxima",
    "run_textbook",
    "textbook_orders",
    "textbook_plate",
    "textbook_rayleigh_lamb",
    "to_json",
    "write_results",
]

NU = sympy.Symbol("nu")
KAPPA = sympy.Symbol("kappa")
_W = sympy.Symbol("W", positive=True)  # Omega^2 in the textbook route
BRANCH_START = {"S0": 1, "A0": 2}  # Omega^2 starts at kappa^(2 sigma)

#: One power-series table: branch -> power of kappa -> coefficient.
Coefficients = dict[str, dict[int, sympy.Expr]]


@dataclass
class RouteResult:
    """One route's attempt at a task: coefficients, time, and whether it finished."""

    route: str
    coefficients: Coefficients = field(default_factory=dict)
    seconds: float | None = None  # None: not run (see note)
    complete: bool = True
    note: str = ""
    #: (highest power of kappa reached, cumulative seconds), for the speed chart.
    progress: list[tuple[int, float]] = field(default_factory=list)


@dataclass
class Row:
    """One line of the table: a task and its routes (``ours`` first)."""

    task: str
    routes: dict[str, RouteResult]
    compared: int = 0
    mismatches: list[str] = field(default_factory=list)
    target_s: float | None = None  # the speed target for our engine, if any


@dataclass
class BenchmarkResult:
    rows: list[Row]
    peak_rss_mib: float
    peak_child_rss_mib: float
    peak_traced_mib: float | None
    settings: dict

    @property
    def agree(self) -> bool:
        return all(not row.mismatches for row in self.rows)


# --------------------------------------------------------------------------- Maxima


def maxima_script() -> Path:
    """Path of ``benchmarks/maxima/rayleigh_lamb_series.mac`` in the source tree."""
    return Path(__file__).resolve().parents[1] / "benchmarks" / "maxima" / "rayleigh_lamb_series.mac"


_COEF = re.compile(r"^COEF\s+(S0|A0)\s+(\d+)\s+(.+?)\s*$")
_TIME = re.compile(r"^TIME\s+([0-9.eE+-]+)\s*$")


def parse_maxima_output(text: str) -> tuple[Coefficients, float | None]:
    """Read the ``COEF <branch> <power> <expr>`` and ``TIME <s>`` lines of the Maxima program.

    Other lines (Maxima's echo and notes) are ignored. Expressions use Maxima's linear syntax
    (``^`` for powers), which sympy parses with ``convert_xor``.
    """
    from sympy.parsing.sympy_parser import convert_xor, parse_expr, standard_transformations

    coeffs: Coefficients = {}
    seconds = None
    for line in text.splitlines():
        if m := _COEF.match(line.strip()):
            expr = parse_expr(m[3], local_dict={"nu": NU},
                              transformations=standard_transformations + (convert_xor,))
            coeffs.setdefault(m[1], {})[int(m[2])] = expr
        elif m := _TIME.match(line.strip()):
            seconds = float(m[1])
    return coeffs, seconds


def run_maxima(order: int = 16, *, executable: str = "maxima", timeout: float = 300.0,
               script: Path | None = None) -> RouteResult:
    """Run the Maxima program for the S0 and A0 series up to ``kappa**order``; wall time.

    Parameters
    ----------
    order : int
        Highest power of :math:`\\kappa` (even, >= 2); the program gets ``N = order // 2``.
    executable : str
        Name or path of the maxima binary.
    timeout : float
        Seconds before the subprocess is stopped (reported, not raised).
    script : Path, optional
        The ``.mac`` program (default :func:`maxima_script`).

    Returns
    -------
    RouteResult
        ``seconds`` is the wall time including Maxima's start-up; ``seconds=None`` and a note
        when maxima or the script is absent.
    """
    order = check_positive_int("order", order, 2)
    exe = shutil.which(executable)
    script = maxima_script() if script is None else Path(script)
    if exe is None:
        return RouteResult("maxima", seconds=None, complete=False,
                           note=f"skipped: {executable!r} not found on PATH")
    if not script.is_file():
        return RouteResult("maxima", seconds=None, complete=False,
                           note=f"skipped: Maxima program {script} not found")
    path = str(script).replace("\\", "/").replace('"', '\\"')
    cmd = [exe, "--very-quiet", f'--batch-string=N : {order // 2}$ batchload("{path}")$']
    start = time.perf_counter()
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, check=False)
    except subprocess.TimeoutExpired:
        return RouteResult("maxima", seconds=timeout, complete=False,
                           note=f"stopped after the {timeout:g} s timeout")
    wall = time.perf_counter() - start
    coeffs, _ = parse_maxima_output(proc.stdout)
    expected = {"S0": order // 2, "A0": order // 2 - 1}
    got = {b: len(coeffs.get(b, {})) for b in expected}
    ok = proc.returncode == 0 and got == expected
    note = "" if ok else f"maxima exit {proc.returncode}, coefficients {got}, expected {expected}"
    return RouteResult("maxima", coeffs, wall, ok, note, [(order, wall)])


# --------------------------------------------------------------------------- textbook route


def textbook_orders(F: sympy.Expr, sigma: int, order: int) -> Iterator[tuple[int, sympy.Expr]]:
    """Textbook power balance on ``F(kappa, W)``: substitute, ``series``, ``solve``.

    ``W = Omega^2 = sum_{j >= sigma} a_j kappa^(2 j)``. At each step the known coefficients
    and one unknown ``A`` are substituted, ``sympy.series`` expands in kappa and ``sympy.solve``
    finds ``A`` from the lowest power not yet balanced (the first time: the non-zero root of the
    lowest non-vanishing coefficient). Yields ``(2 j, a_j)``.
    """
    A = sympy.Symbol("A")
    known = sympy.Integer(0)
    lead = None  # power of kappa of the first balanced equation
    for j in range(sigma, order // 2 + 1):
        expr = F.subs(_W, known + A * KAPPA ** (2 * j))
        if lead is None:
            n = 2 * sigma + 2
            while lead is None:
                ser = sympy.expand(sympy.series(expr, KAPPA, 0, n).removeO())
                for power in range(n):
                    c = sympy.factor(ser.coeff(KAPPA, power))
                    if c != 0:
                        lead, eq = power, c
                        break
                n += 2
                if n > 4 * order + 16:
                    raise InputError("textbook route: no balancing power found")
        else:
            power = lead + 2 * (j - sigma)
            ser = sympy.expand(sympy.series(expr, KAPPA, 0, power + 1).removeO())
            eq = ser.coeff(KAPPA, power)
        roots = sympy.solve(eq, A)
        if j == sigma:  # drop the trivial root Omega = 0 of the first, nonlinear balance
            roots = [s for s in roots if sympy.simplify(s) != 0]
        if len(roots) != 1:
            raise InputError(f"textbook route: {len(roots)} non-zero roots at kappa^{2 * j}")
        a = sympy.factor(roots[0])
        known += a * KAPPA ** (2 * j)
        yield 2 * j, a


def textbook_rayleigh_lamb(branch: str) -> sympy.Expr:
    """The Rayleigh-Lamb function in plain sympy: ``cos(sqrt z)``, ``sin(sqrt z)/sqrt z``."""
    from .rayleigh_lamb import frequency_function

    def C(z):
        return sympy.cos(sympy.sqrt(z))

    def S(z):
        return sympy.sin(sympy.sqrt(z)) / sympy.sqrt(z)

    return frequency_function(branch[0], KAPPA**2, _W, NU, C, S)


def textbook_plate(mass: str = "consistent", model: str = "bloch", r=2, nu=None,
                   **kwargs) -> sympy.Expr:
    """``Matrix.det()`` (sympy's default method) of the full :math:`K_{dyn}` of the paper's
    patch (p = 2, n = 3) with :math:`\\Omega^2` = ``W``; ``nu`` symbolic unless given."""
    from .plate import dynamic_stiffness, plate_patch

    patch = plate_patch(2, 3, model, r if model == "bloch" else None, mass, **kwargs)
    return dynamic_stiffness(patch, KAPPA, sympy.sqrt(_W), NU if nu is None else nu).det()


def _textbook_worker(build: Callable[[], sympy.Expr], branches: tuple[str, ...], order: int,
                     q) -> None:
    start = time.perf_counter()
    try:
        F = build()
        for branch in branches:
            for power, a in textbook_orders(F, BRANCH_START[branch], order):
                q.put(("coef", branch, power, str(a), time.perf_counter() - start))
        q.put(("done", "", 0, "", time.perf_counter() - start))
    except Exception as exc:  # noqa: BLE001 - reported to the parent as a note
        q.put(("error", "", 0, f"{type(exc).__name__}: {exc}", time.perf_counter() - start))


def run_textbook(build: Callable[[], sympy.Expr], branches: tuple[str, ...], order: int,
                 budget: float) -> RouteResult:
    """Run the textbook route in a child process, stopped after ``budget`` seconds.

    ``build()`` returns the characteristic function, computed once for all ``branches`` and
    timed too (the determinant is part of the route). Orders finished in time are kept; if
    stopped, ``complete`` is False and ``seconds`` is the budget (read it as "> budget").
    """
    check_positive("budget", budget)
    ctx = multiprocessing.get_context("fork")
    q = ctx.Queue()
    proc = ctx.Process(target=_textbook_worker, args=(build, tuple(branches), order, q),
                       daemon=True)
    result = RouteResult("textbook", {b: {} for b in branches}, None, False)
    deadline = time.monotonic() + budget
    proc.start()
    try:
        while True:
            try:
                kind, branch, power, text, t = q.get(
                    timeout=max(deadline - time.monotonic(), 0.01))
            except _queue.Empty:
                result.seconds = budget
                result.note = f"stopped after the {budget:g} s budget"
                break
            if kind == "coef":
                result.coefficients[branch][power] = sympy.sympify(text, locals={"nu": NU})
                result.progress.append((power, t))
            elif kind == "done":
                result.seconds, result.complete = t, True
                break
            else:
                result.seconds, result.note = t, text
                break
    finally:
        if proc.is_alive():
            proc.terminate()
        proc.join(5)
    return result


# --------------------------------------------------------------------------- comparison


def compare(a: Coefficients, b: Coefficients) -> tuple[int, list[str]]:
    """Number of coefficients both tables hold, and a description of each that differs."""
    count, bad = 0, []
    for branch, coeffs in a.items():
        for power, value in coeffs.items():
            other = b.get(branch, {}).get(power)
            if other is None:
                continue
            count += 1
            if sympy.cancel(sympy.sympify(value) - other) != 0:
                bad.append(f"{branch} kappa^{power}: {value} != {other}")
    return count, bad


# --------------------------------------------------------------------------- our engine


def _ours(jobs: list[tuple[str, dict]], order: int) -> RouteResult:
    """Time our engine on ``jobs`` = [(branch, kwargs of discrete_series or {"exact": True})]."""
    from . import power_balance

    coeffs: Coefficients = {}
    start = time.perf_counter()
    for branch, kw in jobs:
        kw = dict(kw)
        if kw.pop("exact", False):
            series = power_balance.exact_series(branch, order)
        else:
            series = power_balance.discrete_series(branch, order, **kw)
        coeffs.setdefault(_label(branch, kw), {}).update(series)
    seconds = time.perf_counter() - start
    return RouteResult("ours", coeffs, seconds, True, "", [(order, seconds)])


def _label(branch: str, kw: dict) -> str:
    mass = kw.get("mass")
    return branch if mass is None else f"{branch}/{mass}"


def _clear_caches() -> None:
    """Empty memoised results so a timed run computes from scratch (fair to the baselines)."""
    from . import plate, power_balance

    for module in (plate, power_balance):
        for obj in vars(module).values():
            if callable(getattr(obj, "cache_clear", None)):
                obj.cache_clear()


# --------------------------------------------------------------------------- the benchmark


PAPER_MASSES = ("consistent", "lumped", "singular")
SINGULAR = {"contact": "top", "gamma_s": 0}


def _mass_kwargs(mass: str, model: str, r) -> dict:
    kw = {"mass": mass, "model": model, "r": r if model == "bloch" else None}
    if mass == "singular":
        kw.update(SINGULAR)
    return kw


def run_benchmark(quick: bool = False, *, budget: float | None = None, model: str = "bloch",
                  r=2, maxima: str = "maxima",
                  progress: Callable[[str], None] | None = None) -> BenchmarkResult:
    """Run every task with every route, compare the coefficients, return the table.

    Parameters
    ----------
    quick : bool
        Orders up to kappa^8 only and a 10 s textbook budget (CI).
    budget : float, optional
        Seconds per textbook job (default 120; quick 10).
    model, r :
        x-model of the plate patch (default the paper's: Bloch, square elements b = 2h).
    maxima : str
        The maxima executable; absent -> the Maxima column says "skipped".
    progress : callable, optional
        Receives one line per step (the CLI prints them on stderr).

    Notes
    -----
    Tasks: the paper set (eqs 14-20 and kappa^8: exact S0/A0 and the CMM, lumped and singular
    discrete S0/A0 series); CMM and singular to kappa^12; the exact Rayleigh-Lamb S0/A0 series
    to kappa^16. The textbook route runs on the CMM rows and on Rayleigh-Lamb, with ``budget``
    seconds per job (one determinant with its branches, or one Rayleigh-Lamb branch).
    ``quick`` lowers the orders and the budget (for CI).
    """
    say = progress or (lambda msg: None)
    budget = (10.0 if quick else 120.0) if budget is None else float(check_positive("budget", budget))
    rl_order, high_order = (8, 8) if quick else (16, 12)
    from . import power_balance  # imported before the timings: warm interpreter

    # Warm-up: compile the code paths once on a small, different problem, then drop caches.
    power_balance.discrete_series("S0", 2, p=2, n=3, model="x-exact")
    _clear_caches()
    rows: list[Row] = []

    def textbook_jobs(masses, order) -> RouteResult:
        total = RouteResult("textbook", {}, 0.0, True)
        for mass in masses:
            kw = _mass_kwargs(mass, model, r)
            extra = {k: kw[k] for k in ("contact", "gamma_s") if k in kw}
            say(f"textbook det route: {mass} S0, A0 to kappa^{order} (budget {budget:g} s)")
            res = run_textbook(
                lambda mass=mass, extra=extra: textbook_plate(mass, model, r, **extra),
                ("S0", "A0"), order, budget)
            for branch, coeffs in res.coefficients.items():
                total.coefficients[f"{branch}/{mass}"] = coeffs
            total.seconds += res.seconds or 0.0
            total.complete &= res.complete
            if res.note:
                total.note += f"{mass}: {res.note}; "
        return total

    # 1. the paper set: eqs 14-20 and the next order
    say("ours: paper set (eqs 14-20 + kappa^8)")
    jobs = [(b, {"exact": True}) for b in ("S0", "A0")]
    jobs += [(b, _mass_kwargs(m, model, r)) for m in PAPER_MASSES for b in ("S0", "A0")]
    _clear_caches()
    ours = _ours(jobs, 8)
    rows.append(Row("eqs 14-20 + kappa^8 (exact; CMM, lumped, singular)", {"ours": ours},
                    target_s=3.0))
    say("ours: CMM S0, A0 to kappa^8")
    _clear_caches()
    ours = _ours([(b, _mass_kwargs("consistent", model, r)) for b in ("S0", "A0")], 8)
    rows.append(Row("CMM S0 + A0 to kappa^8 (eqs 17-18 + next order)",
                    {"ours": ours, "textbook": textbook_jobs(("consistent",), 8)}))

    # 2. CMM and singular to kappa^12
    if not quick:
        say(f"ours: CMM and singular to kappa^{high_order}")
        jobs = [(b, _mass_kwargs(m, model, r)) for m in ("consistent", "singular")
                for b in ("S0", "A0")]
        _clear_caches()
        ours = _ours(jobs, high_order)
        rows.append(Row(f"CMM + singular to kappa^{high_order}", {"ours": ours}, target_s=10.0))

    # 3. exact Rayleigh-Lamb to kappa^16, with Maxima
    say(f"ours: Rayleigh-Lamb S0, A0 to kappa^{rl_order}")
    _clear_caches()
    ours = _ours([(b, {"exact": True}) for b in ("S0", "A0")], rl_order)
    say(f"maxima: Rayleigh-Lamb S0, A0 to kappa^{rl_order}")
    mx = run_maxima(rl_order, executable=maxima)
    tb = RouteResult("textbook", {}, 0.0, True)
    for branch in ("S0", "A0"):
        say(f"textbook series route: Rayleigh-Lamb {branch} (budget {budget:g} s)")
        res = run_textbook(lambda branch=branch: textbook_rayleigh_lamb(branch), (branch,),
                           rl_order, budget)
        tb.coefficients.update(res.coefficients)
        tb.seconds += res.seconds or 0.0
        tb.complete &= res.complete
        tb.progress.extend(res.progress)
        if res.note:
            tb.note += f"{branch}: {res.note}; "
    rows.append(Row(f"Rayleigh-Lamb S0 + A0 to kappa^{rl_order}",
                    {"ours": ours, "maxima": mx, "textbook": tb}))

    for row in rows:
        for name, route in row.routes.items():
            if name == "ours":
                continue
            n, bad = compare(row.routes["ours"].coefficients, route.coefficients)
            row.compared += n
            row.mismatches += [f"{name}: {b}" for b in bad]

    # Python-heap peak of our engine on the paper set (a separate, untimed run).
    peak_traced = None
    if not quick:
        import tracemalloc

        _clear_caches()
        tracemalloc.start()
        _ours([(b, _mass_kwargs(m, model, r)) for m in PAPER_MASSES for b in ("S0", "A0")], 8)
        peak_traced = tracemalloc.get_traced_memory()[1] / 2**20
        tracemalloc.stop()

    self_rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    child_rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    settings = {"quick": quick, "budget_s": budget, "model": model, "r": str(r),
                "singular": SINGULAR, "cpu_count": os.cpu_count(),
                "sympy": sympy.__version__, "ground_types": _ground_types()}
    return BenchmarkResult(rows, self_rss, child_rss, peak_traced, settings)


def _ground_types() -> str:
    from sympy.external.gmpy import GROUND_TYPES

    return GROUND_TYPES


def order_sweep(quick: bool = False, *, budget: float | None = None, model: str = "bloch",
                r=2, maxima: str = "maxima") -> dict:
    """Seconds each route needs to reach each order, S0 and A0 together (the speed chart).

    Problems: ``"rayleigh_lamb"`` (ours, Maxima, textbook series) and ``"cmm"`` (the paper's
    patch with CMM: ours, textbook determinant). Ours and Maxima are run afresh per order;
    the textbook route streams its orders, so its times are cumulative (S0 time to reach the
    order plus A0 time to reach it, each including its own ``Matrix.det``). Returns
    ``{problem: {route: [[order, seconds], ...]}, "budget_s": budget, "notes": [...]}``.
    """
    from . import power_balance

    budget = (5.0 if quick else 60.0) if budget is None else float(check_positive("budget", budget))
    rl_orders = (4, 8) if quick else (4, 8, 12, 16)
    cmm_orders = (4, 8) if quick else (4, 8, 12)
    power_balance.discrete_series("S0", 2, model="x-exact")  # warm-up, then caches dropped
    cmm = _mass_kwargs("consistent", model, r)
    out: dict = {"rayleigh_lamb": {"ours": [], "maxima": [], "textbook": []},
                 "cmm": {"ours": [], "textbook": []}, "budget_s": budget, "notes": [],
                 "model": model, "r": str(r)}
    for order in rl_orders:
        _clear_caches()
        out["rayleigh_lamb"]["ours"].append(
            [order, _ours([(b, {"exact": True}) for b in ("S0", "A0")], order).seconds])
        mx = run_maxima(order, executable=maxima)
        if mx.complete:
            out["rayleigh_lamb"]["maxima"].append([order, mx.seconds])
        elif mx.note and mx.note not in out["notes"]:
            out["notes"].append(f"maxima: {mx.note}")
    for order in cmm_orders:
        _clear_caches()
        out["cmm"]["ours"].append([order, _ours([(b, cmm) for b in ("S0", "A0")], order).seconds])

    extra = {k: cmm[k] for k in ("contact", "gamma_s") if k in cmm}
    builds = {"rayleigh_lamb": lambda b: (lambda: textbook_rayleigh_lamb(b)),
              "cmm": lambda b: (lambda: textbook_plate("consistent", model, r, **extra))}
    for problem, orders in (("rayleigh_lamb", rl_orders), ("cmm", cmm_orders)):
        reached = {}
        for branch in ("S0", "A0"):
            res = run_textbook(builds[problem](branch), (branch,), max(orders), budget)
            reached[branch] = dict(res.progress)
            if res.note:
                out["notes"].append(f"textbook {problem} {branch}: {res.note}")
        both = sorted(set(reached["S0"]) & set(reached["A0"]) - {2})
        out[problem]["textbook"] = [[k, reached["S0"][k] + reached["A0"][k]] for k in both]
    return out


# --------------------------------------------------------------------------- output


def _cell(route: RouteResult | None) -> str:
    if route is None or route.seconds is None:
        return "skipped" if route is not None else "-"
    return f"{route.seconds:.3g}" if route.complete else f"> {route.seconds:.3g}"


def _ratio(ours: RouteResult, other: RouteResult | None) -> str:
    if other is None or other.seconds is None or not ours.seconds:
        return "-"
    ratio = other.seconds / ours.seconds
    return f"{ratio:.3g}" if other.complete else f"> {ratio:.3g}"


def format_table(result: BenchmarkResult) -> str:
    """Markdown table: task, ours [s], each baseline [s] and its ratio to ours, agreement."""
    lines = ["| task | ours [s] | target | textbook [s] | ratio | maxima [s] | ratio | agree |",
             "|---|---|---|---|---|---|---|---|"]
    for row in result.rows:
        ours, tb, mx = (row.routes.get(k) for k in ("ours", "textbook", "maxima"))
        agree = (f"{row.compared} coeffs" if not row.mismatches
                 else f"MISMATCH ({len(row.mismatches)})")
        target = "-" if row.target_s is None else (
            f"< {row.target_s:g} s: " + ("met" if ours.seconds < row.target_s else "MISSED"))
        lines.append(f"| {row.task} | {_cell(ours)} | {target} | {_cell(tb)} | "
                     f"{_ratio(ours, tb)} | {_cell(mx)} | {_ratio(ours, mx)} | {agree} |")
    lines.append("")
    lines.append(f"Peak RSS: this process {result.peak_rss_mib:.0f} MiB, largest child "
                 f"(textbook worker / maxima) {result.peak_child_rss_mib:.0f} MiB"
                 + (f"; Python-heap peak of our engine on the paper set "
                    f"{result.peak_traced_mib:.1f} MiB (tracemalloc)."
                    if result.peak_traced_mib is not None else "."))
    notes = [f"- {row.task}, {name}: {route.note}" for row in result.rows
             for name, route in row.routes.items() if route.note]
    notes += [f"- {row.task}: {m}" for row in result.rows for m in row.mismatches]
    if notes:
        lines += ["", "Notes:", *notes]
    return "\n".join(lines) + "\n"


def to_json(result: BenchmarkResult) -> dict:
    """Plain-data form (coefficients as sympy-parsable strings)."""
    def route(r: RouteResult) -> dict:
        d = asdict(r)
        d["coefficients"] = {b: {str(k): str(v) for k, v in c.items()}
                             for b, c in r.coefficients.items()}
        return d

    return {
        "settings": result.settings,
        "peak_rss_mib": result.peak_rss_mib,
        "peak_child_rss_mib": result.peak_child_rss_mib,
        "peak_traced_mib": result.peak_traced_mib,
        "agree": result.agree,
        "rows": [{"task": row.task, "compared": row.compared, "mismatches": row.mismatches,
                  "target_s": row.target_s,
                  "routes": {k: route(v) for k, v in row.routes.items()}}
                 for row in result.rows],
    }


def write_results(result: BenchmarkResult, out: Path) -> list[Path]:
    """Write ``bench_series.json`` and ``bench_series.md`` into ``out`` (atomically)."""
    import json

    from .io import write_text

    out = Path(out)
    return [write_text(out / "bench_series.json", json.dumps(to_json(result), indent=1) + "\n"),
            write_text(out / "bench_series.md", format_table(result))]
