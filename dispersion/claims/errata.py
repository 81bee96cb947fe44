"""Errata of the paper's eqs (13)-(20): the printed terms against the derivation.

The printed formulas are data, the claims file ``dispersion/data/paper_claims.toml``
(:func:`dispersion.claims.paper_claims_path`), never results. Each row of :func:`errata_table`
holds one printed term of a series claim of that file (eqs 14-20), the derived coefficient
under the claim's model, the status, and which discrete models reproduce the printed term
(Bloch with square elements b = 2h, r = 2; x-exact; Bloch with h/b = 2, r = 1/2, the aspect
ratio of the paper's Figure 2 caption). ``dispersion verify`` on the same file exits 1 and
names eqs 17 and 19; the table is a report and never fails.

>>> rows = errata_table(equations=("18",))
>>> [(r.power, r.status) for r in rows]
[(4, 'match'), (6, 'match')]

References
----------
A. Tkachuk, M. Matzen, R. Kolman, M. Bischoff, eqs (13)-(20).
"""
from __future__ import annotations

import re
from dataclasses import dataclass

import sympy

from dispersion import defaults
from dispersion.claims.claim import Claim
from dispersion.claims.claims_file import paper_claims_path
from dispersion.claims.exact_model import ExactModel
from dispersion.claims.schema import load_claims
from dispersion.claims.verify import ClaimResult, _same, _series, verify_claims
from dispersion.errors import InputError
from dispersion.continuum.exact_series import exact_leading_balance

__all__ = ["MODELS_TRIED", "ErrataRow", "PaperErrata", "paper_claims", "errata_table",
           "format_table", "errata_document", "eq13_note", "paper_errata"]

#: candidate x-models, label -> the fields of the claim's :class:`~dispersion.symbolic.patch.Patch`
#: they replace; the claim's own patch is derived first
MODELS_TRIED = {
    "bloch r=2": dict(model="bloch", r=defaults.R),
    "x-exact": dict(model="x-exact", r=None),
    "bloch r=1/2": dict(model="bloch", r=defaults.FIGURE2_R),
}


@dataclass(frozen=True)
class ErrataRow:
    """One printed term: ``equation`` is the claim's label, e.g. ``"17"``."""

    equation: str
    branch: str
    power: int
    printed: sympy.Expr
    derived: sympy.Expr
    status: str  # "match" or "differs"
    reproduced_by: tuple[str, ...]
    setting: str
    printed_latex: str = ""
    derived_latex: str = ""


@dataclass(frozen=True)
class PaperErrata:
    """The paper's claims file verified, its errata rows and the eq (13) leading balances."""

    claims_file: str
    claims: tuple[ClaimResult, ...]
    rows: tuple[ErrataRow, ...]
    eq13: tuple[tuple[str, str, str], ...]
    seconds: float
    passed: bool


def _label(claim: Claim) -> str:
    return re.sub(r"^eq\s*", "", claim.name)


def _number(claim: Claim) -> str:
    """The equation number of a claim's label: ``"20"`` for ``"eq 20, gamma_s = 1/2"``."""
    return _label(claim).split(",")[0].strip()


def paper_claims(equations=None) -> list[Claim]:
    """Series claims of the paper's file, optionally only those of the given equations.

    ``equations`` is a collection of equation numbers (``"18"`` or ``18``; a single one may be
    given bare); each must name a series claim of the file, else :class:`InputError`.

    >>> [c.name for c in paper_claims(equations=18)]
    ['eq 18']
    >>> paper_claims(equations=("99",))
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: equations must name equations of the paper's claims file (one of 14, 15, 17, 18, 19, 20); got '99'
    """
    claims = [c for c in load_claims(paper_claims_path()) if c.kind == "series"]
    if equations is None:
        return claims
    known = tuple(dict.fromkeys(_number(c) for c in claims))
    if isinstance(equations, (str, int)) and not isinstance(equations, bool):
        equations = (equations,)
    try:
        asked = tuple(equations)
    except TypeError:
        raise InputError(f"equations must be a collection of equation numbers (one of "
                         f"{', '.join(known)}); got {equations!r}") from None
    for eq in asked:
        if isinstance(eq, bool) or not isinstance(eq, (str, int)) or str(eq).strip() not in known:
            raise InputError(f"equations must name equations of the paper's claims file "
                             f"(one of {', '.join(known)}); got {eq!r}")
    wanted = {str(eq).strip() for eq in asked}
    return [c for c in claims if _number(c) in wanted]


def _reproduced(claim: Claim, power: int, printed, models: dict) -> tuple[str, ...]:
    if isinstance(claim.model, ExactModel):
        return ("exact",) if _same(_series(claim.model, claim.branch, claim.order)[power],
                                   printed) else ()
    hits = []
    for label, fields in models.items():
        model = claim.model.replace(**fields)
        if _same(_series(model, claim.branch, claim.order).get(power, 0), printed):
            hits.append(label)
    return tuple(hits)


def errata_table(equations=("14", "15", "17", "18", "19", "20"),
                 models: dict | None = None) -> list[ErrataRow]:
    """Derive every printed term of the paper's series claims and compare; see the module doc.

    ``equations`` as in :func:`paper_claims` (checked before any derivation).
    """
    models = MODELS_TRIED if models is None else models
    rows = []
    for claim in paper_claims(equations):
        derived = _series(claim.model, claim.branch, claim.order)
        for power, printed in claim.printed:
            ours = derived.get(power, sympy.Integer(0))
            rows.append(ErrataRow(
                _label(claim), claim.branch, power, printed, ours,
                "match" if _same(ours, printed) else "differs",
                _reproduced(claim, power, printed, models), claim.model.label(),
                sympy.latex(printed), sympy.latex(ours)))
    return rows


def eq13_note() -> list[tuple[str, str, str]]:
    """Leading balances of the printed and the standard eq (13): (branch, standard, printed)."""
    return [(b, str(exact_leading_balance(b, "standard")), str(exact_leading_balance(b, "printed")))
            for b in ("S0", "A0")]


def paper_errata(quick: bool = False, executor=None) -> PaperErrata:
    """Verify the paper's claims file and build its errata rows (the coefficients section).

    ``quick`` is accepted for the report protocol (the work is the same); ``executor`` runs
    independent derivations (see :func:`dispersion.claims.verify_claims`).
    """
    claims = load_claims(paper_claims_path())
    verified = verify_claims(claims, executor=executor, jobs=None if executor else 1)
    rows = errata_table()
    return PaperErrata(str(paper_claims_path().name), verified.results, tuple(rows),
                       tuple(tuple(x) for x in eq13_note()), verified.seconds, verified.passed)


def _get(row, name):
    return row[name] if isinstance(row, dict) else getattr(row, name)


_TEX_SPECIAL = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#",
                "_": r"\_", "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}",
                "^": r"\^{}"}


def _tex(text: str) -> str:
    """Plain text escaped for LaTeX."""
    return "".join(_TEX_SPECIAL.get(ch, ch) for ch in str(text))


def _expr(value, names: tuple[str, ...] = ()):
    """An expression of a row: text (from JSON) read by the whitelist reader, never sympified."""
    from dispersion.claims.reader import read

    return read(value, names=names) if isinstance(value, str) else value


def format_table(rows, fmt: str = "text") -> str:
    """Render errata rows (objects or their JSON dictionaries) as ``text``, ``markdown``, ``latex``.

    The LaTeX form is a ``tabular`` that compiles inside any document; :func:`errata_document`
    wraps it into a complete one.
    """
    head = ("eq", "term", "printed", "derived", "status", "reproduced by")

    def cells(r):
        if fmt == "latex":
            printed = _get(r, "printed_latex") or sympy.latex(_expr(_get(r, "printed")))
            derived = _get(r, "derived_latex") or sympy.latex(_expr(_get(r, "derived")))
        else:
            printed, derived = str(_get(r, "printed")), str(_get(r, "derived"))
        return (f"({_get(r, 'equation')})", f"kappa^{_get(r, 'power')}", printed, derived,
                _get(r, "status"), ", ".join(_get(r, "reproduced_by")) or "none")

    body = [cells(r) for r in rows]
    if fmt == "markdown":
        from dispersion.table import markdown_table

        return markdown_table(head, body)
    if fmt == "latex":
        lines = [r"\begin{tabular}{llllll}", " & ".join(head) + r" \\ \hline"]
        for row in body:
            tex = [f"${c}$" if i in (2, 3) else _tex(c) for i, c in enumerate(row)]
            tex[1] = rf"$\kappa^{{{row[1].split('^')[1]}}}$"
            lines.append(" & ".join(tex) + r" \\")
        return "\n".join(lines + [r"\end{tabular}"])
    from dispersion.table import text_table

    return text_table(head, body)


def errata_document(rows, eq13=None, title: str = "Errata of eqs (13)-(20)") -> str:
    """A complete LaTeX document: the errata table and, if given, the eq (13) balances.

    ``eq13`` is :func:`eq13_note` (or its JSON form). Compiles with ``pdflatex`` from
    ``texlive-latex-base`` alone (packages: amsmath, geometry, longtable): a landscape page,
    the table breaking across pages.
    """
    table = format_table(rows, "latex").replace(r"{tabular}", r"{longtable}")
    parts = [r"\documentclass{article}", r"\usepackage{amsmath}",
             r"\usepackage[a4paper,landscape,margin=1.5cm]{geometry}", r"\usepackage{longtable}",
             r"\renewcommand{\arraystretch}{2.2}", r"\begin{document}",
             rf"\section*{{{_tex(title)}}}", r"\small", table, r"\normalsize"]
    if eq13:
        parts += [r"\subsection*{Eq (13): leading balance $q_0(w)$ for "
                  r"$\Omega^2 = w\,\kappa^{2\sigma}$}", r"\begin{itemize}"]
        for branch, standard, printed in eq13:
            parts.append(rf"\item {_tex(branch)}: standard "
                         rf"${sympy.latex(_expr(standard, ('w',)))}$; printed "
                         rf"${sympy.latex(_expr(printed, ('w',)))}$")
        parts.append(r"\end{itemize}")
    return "\n".join(parts + [r"\end{document}"]) + "\n"
