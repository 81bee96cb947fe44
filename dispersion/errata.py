"""Paper eqs (13)-(20) as printed, checked against the derivation of this toolkit.

The printed formulas below are transcribed from the paper as references to check, never used
as results. Each row of :func:`errata_table` holds the equation, the power of kappa, the
printed and the derived coefficient, the status, and which discrete models reproduce the
printed term (x-exact; Bloch with square elements b = 2h, r = 2; Bloch with h/b = 2, r = 1/2,
the aspect ratio of the paper's Figure 2 caption).

>>> rows = errata_table(equations=("18",))
>>> [(r.power, r.status) for r in rows]
[(4, 'match'), (6, 'match')]

References
----------
A. Tkachuk, M. Matzen, R. Kolman, M. Bischoff, eqs (13)-(20).
"""
from __future__ import annotations

from dataclasses import dataclass

import sympy

from .power_balance import NU, discrete_series, exact_leading_balance, exact_series

__all__ = ["PRINTED", "MODELS_TRIED", "PAPER_SETTINGS", "ErrataRow", "errata_table",
           "format_table", "eq13_note"]

nu = NU
_R = sympy.Rational

#: eqs (14)-(20) as printed: {equation: (branch, {power of kappa: coefficient of Omega^2})}
PRINTED: dict[str, tuple[str, dict[int, sympy.Expr]]] = {
    "14": ("S0", {2: 2 / (1 - nu), 4: -2 * nu**2 / (3 * (1 - nu) ** 3),
                  6: 2 * nu**2 * (7 * nu**2 + 10 * nu - 6) / (45 * (1 - nu) ** 5)}),
    "15": ("A0", {4: 2 / (3 * (1 - nu)), 6: 2 * (7 * nu - 17) / (45 * (1 - nu) ** 2)}),
    "17": ("S0", {2: 2 / (1 - nu), 4: -2 * nu**2 / (3 * (1 - nu) ** 3),
                  6: -(2 * nu**6 - 18 * nu**5 + nu**4 + 10 * nu**2 - 6 * nu + 1)
                  / (45 * (1 - nu) ** 5 * (1 - 2 * nu))}),
    "18": ("A0", {4: 2 / (3 * (1 - nu)), 6: (2 * nu**2 + 8 * nu - 29) / (45 * (1 - nu) ** 2)}),
    "19": ("S0", {2: 2 / (1 - nu), 4: -2 * (41 * nu**2 - 10 * nu - 35) / (45 * (1 - nu) ** 3)}),
    "20": ("A0", {4: 2 / (3 * (1 - nu)), 6: (2 * nu**2 - 16 * nu - 25) / (45 * (1 - nu) ** 2)}),
}

#: mass settings of each discrete equation (singular: contact on the top surface, the
#: contact shape function moved wholly to its neighbour through the thickness)
PAPER_SETTINGS = {
    "17": dict(mass="consistent"), "18": dict(mass="consistent"),
    "19": dict(mass="singular", contact="top", gamma_s=0),
    "20": dict(mass="singular", contact="top", gamma_s=0),
}

#: candidate x-models, label -> plate_patch keywords; the first is the one derived in the table
MODELS_TRIED = {
    "bloch r=2": dict(model="bloch", r=2),
    "x-exact": dict(model="x-exact"),
    "bloch r=1/2": dict(model="bloch", r=_R(1, 2)),
}


@dataclass(frozen=True)
class ErrataRow:
    equation: str
    branch: str
    power: int
    printed: sympy.Expr
    derived: sympy.Expr
    status: str
    reproduced_by: tuple[str, ...]
    setting: str


def _same(a, b) -> bool:
    return sympy.cancel(sympy.together(a - b)) == 0


def errata_table(equations=("14", "15", "17", "18", "19", "20"),
                 models: dict | None = None) -> list[ErrataRow]:
    """Derive every printed term and compare; see the module docstring."""
    models = MODELS_TRIED if models is None else models
    rows = []
    for eq in equations:
        branch, printed = PRINTED[eq]
        order = max(printed)
        if eq in PAPER_SETTINGS:
            derived = {label: discrete_series(branch, order, **kw, **PAPER_SETTINGS[eq])
                       for label, kw in models.items()}
            first = next(iter(models))
            setting = f"{first}, " + ", ".join(f"{k}={v}" for k, v in PAPER_SETTINGS[eq].items())
        else:
            derived = {"exact": exact_series(branch, order)}
            first, setting = "exact", "Rayleigh-Lamb (standard form)"
        for power, value in sorted(printed.items()):
            ours = derived[first][power]
            hits = tuple(label for label, ser in derived.items() if _same(ser[power], value))
            rows.append(ErrataRow(eq, branch, power, sympy.factor(value), ours,
                                  "match" if _same(ours, value) else "differs", hits, setting))
    return rows


def eq13_note() -> list[tuple[str, str, str]]:
    """Leading balances of the printed and the standard eq (13): (branch, standard, printed)."""
    return [(b, str(exact_leading_balance(b, "standard")), str(exact_leading_balance(b, "printed")))
            for b in ("S0", "A0")]


def format_table(rows: list[ErrataRow], fmt: str = "text") -> str:
    """Render the errata rows as ``text`` (aligned), ``markdown`` or ``latex``."""
    head = ("eq", "term", "printed", "derived", "status", "reproduced by")

    def cells(r):
        show = sympy.latex if fmt == "latex" else str
        return (f"({r.equation})", f"kappa^{r.power}", show(r.printed), show(r.derived), r.status,
                ", ".join(r.reproduced_by) or "none")

    body = [cells(r) for r in rows]
    if fmt == "markdown":
        lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
        lines += ["| " + " | ".join(c.replace("|", "\\|") for c in row) + " |" for row in body]
        return "\n".join(lines)
    if fmt == "latex":
        lines = [r"\begin{tabular}{llllll}", " & ".join(head) + r" \\ \hline"]
        lines += [" & ".join(f"${c}$" if i in (2, 3) else c.replace("^", r"\^{}")
                             for i, c in enumerate(row)) + r" \\" for row in body]
        return "\n".join(lines + [r"\end{tabular}"])
    widths = [max(len(x) for x in col) for col in zip(head, *body)]
    return "\n".join("  ".join(c.ljust(w) for c, w in zip(row, widths)).rstrip()
                     for row in [head, *body])
