"""The paper's errata as one answer: ``dispersion series --paper`` as a function.

:func:`errata_sheet` derives eqs (14)-(20) and compares them with the printed terms
(:func:`dispersion.claims.errata.errata_table`), adds the leading balance of eq (13) as
printed and in its standard form (:func:`~dispersion.claims.errata.eq13_note`) and returns an
:class:`ErrataSheet`, which renders itself: a table (or, on a narrow terminal, one block per
term), CSV, JSON, Markdown and a complete LaTeX document
(:func:`~dispersion.claims.errata.errata_document`).

>>> sheet = errata_sheet(equations=("18",))
>>> sheet
<ErrataSheet: Errata of the paper's eqs (13)-(20): printed terms against the derivation (2 rows)>
>>> [(r["eq"], r["term"], r["status"]) for r in sheet.rows()]
[('(18)', 'kappa^4', 'match'), ('(18)', 'kappa^6', 'match')]

References
----------
A. Tkachuk, M. Matzen, R. Kolman, M. Bischoff, eqs (13)-(20).
"""
from __future__ import annotations

import textwrap
from dataclasses import dataclass

from dispersion.rendering import Rendered

__all__ = ["ErrataSheet", "errata_sheet"]


def _wrap(text: str, width: int, indent: str) -> str:
    return textwrap.fill(text, width, initial_indent=indent, subsequent_indent=indent + "    ",
                         break_on_hyphens=False)


@dataclass(frozen=True, repr=False)  # Rendered: short repr; every format from the rows
class ErrataSheet(Rendered):
    """Errata rows (:class:`~dispersion.claims.errata.ErrataRow`) and the eq (13) balances
    ``(branch, standard, printed)``."""

    errata: tuple
    eq13: tuple

    def title(self) -> str:
        return "Errata of the paper's eqs (13)-(20): printed terms against the derivation"

    def header_lines(self) -> list[str]:
        from dispersion.claims.claims_file import paper_claims_path

        return [f"printed terms: the claims file {paper_claims_path().name} of the package",
                "reproduced by: the discrete models whose derived term equals the printed one "
                "(Bloch r = b/h = 2, x-exact, Bloch r = 1/2)"]

    def columns(self) -> tuple[str, ...]:
        return ("eq", "term", "printed", "derived", "status", "reproduced by", "setting")

    def text_columns(self) -> tuple[str, ...]:
        return self.columns()[:-1]

    def rows(self) -> list[dict]:
        return [{"eq": f"({r.equation})", "term": f"kappa^{r.power}", "printed": str(r.printed),
                 "derived": str(r.derived), "status": r.status,
                 "reproduced by": ", ".join(r.reproduced_by) or "none", "setting": r.setting}
                for r in self.errata]

    def json_extra(self) -> dict:
        return {"eq13_leading_balance": [dict(zip(("branch", "standard", "printed"), x))
                                         for x in self.eq13]}

    def to_text(self, digits: int = 7, width: int | None = None) -> str:
        """The table, or one block per term where the table is wider than ``width`` (the
        terminal's columns); then the eq (13) balances."""
        import shutil

        from dispersion.claims.errata import format_table

        width = width or max(40, shutil.get_terminal_size((80, 24)).columns)
        table = format_table(self.errata, "text")
        if max(map(len, table.splitlines())) > width:
            table = "\n\n".join(self._block(r, width) for r in self.errata)
        notes = "\n".join(_wrap(f"{b}: standard q0(w) = {s};  printed q0(w) = {p}", width, "  ")
                          for b, s, p in self.eq13)
        return (table + "\n\n" + _wrap("Eq (13), leading balance for Omega^2 = w "
                                       "kappa^(2 sigma) (non-zero roots are admissible leading "
                                       "coefficients):", width, "") + "\n" + notes)

    @staticmethod
    def _block(r, width: int) -> str:
        head = (f"({r.equation}) {r.branch} kappa^{r.power}: {r.status}; reproduced by "
                f"{', '.join(r.reproduced_by) or 'none'}")
        return "\n".join([_wrap(head, width, ""), _wrap(f"printed: {r.printed}", width, "  "),
                          _wrap(f"derived: {r.derived}", width, "  ")])

    def to_latex(self) -> str:
        """A complete LaTeX document (``pdflatex`` with amsmath, geometry, longtable)."""
        from dispersion.claims.errata import errata_document

        return errata_document(self.errata, self.eq13).rstrip("\n")


def errata_sheet(equations=("14", "15", "17", "18", "19", "20")) -> ErrataSheet:
    """The errata of ``equations`` and the eq (13) balances (see the module docstring)."""
    from dispersion.claims.errata import eq13_note, errata_table

    return ErrataSheet(tuple(errata_table(equations)), tuple(eq13_note()))
