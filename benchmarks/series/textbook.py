"""The textbook sympy route, a baseline for the series benchmark (not part of the package).

sympy ``Matrix.det`` of :math:`K_{dyn}` (or the Rayleigh-Lamb function with sympy
``cos``/``sin``), then :math:`\\Omega^2 = \\sum_j a_j \\kappa^{2j}` substituted, ``series`` in
:math:`\\kappa` and ``solve`` order by order, in a child process under a time budget.
"""
from __future__ import annotations

import multiprocessing
import queue as _queue
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import sympy

NU = sympy.Symbol("nu")
KAPPA = sympy.Symbol("kappa")
_W = sympy.Symbol("W", positive=True)  # Omega^2 in the textbook route
BRANCH_START = {"S0": 1, "A0": 2}


@dataclass
class TextbookResult:
    coefficients: dict = field(default_factory=dict)
    seconds: float | None = None
    complete: bool = True
    note: str = ""
    progress: list = field(default_factory=list)


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
                    raise RuntimeError("textbook route: no balancing power found")
        else:
            power = lead + 2 * (j - sigma)
            ser = sympy.expand(sympy.series(expr, KAPPA, 0, power + 1).removeO())
            eq = ser.coeff(KAPPA, power)
        roots = sympy.solve(eq, A)
        if j == sigma:  # drop the trivial root Omega = 0 of the first, nonlinear balance
            roots = [s for s in roots if sympy.simplify(s) != 0]
        if len(roots) != 1:
            raise RuntimeError(f"textbook route: {len(roots)} non-zero roots at kappa^{2 * j}")
        a = sympy.factor(roots[0])
        known += a * KAPPA ** (2 * j)
        yield 2 * j, a


def textbook_rayleigh_lamb(branch: str) -> sympy.Expr:
    """The Rayleigh-Lamb function in plain sympy: ``cos(sqrt z)``, ``sin(sqrt z)/sqrt z``."""
    from dispersion.continuum.rayleigh_lamb import frequency_function

    def C(z):
        return sympy.cos(sympy.sqrt(z))

    def S(z):
        return sympy.sin(sympy.sqrt(z)) / sympy.sqrt(z)

    return frequency_function(branch[0], KAPPA**2, _W, NU, C, S)


def textbook_plate(mass: str = "consistent", model: str = "bloch", r=2, nu=None,
                   **kwargs) -> sympy.Expr:
    """``Matrix.det()`` (sympy's default method) of the full :math:`K_{dyn}` of the paper's
    patch (p = 2, n = 3) with :math:`\\Omega^2` = ``W``; ``nu`` symbolic unless given."""
    from dispersion.symbolic.plate import dynamic_stiffness, plate_patch

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
                 budget: float) -> TextbookResult:
    """Run the textbook route in a child process, stopped after ``budget`` seconds.

    ``build()`` returns the characteristic function, computed once for all ``branches`` and
    timed too (the determinant is part of the route). Orders finished in time are kept; if
    stopped, ``complete`` is False and ``seconds`` is the budget (read it as "> budget").
    """
    ctx = multiprocessing.get_context("fork")
    q = ctx.Queue()
    proc = ctx.Process(target=_textbook_worker, args=(build, tuple(branches), order, q),
                       daemon=True)
    result = TextbookResult({b: {} for b in branches}, None, False)
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
