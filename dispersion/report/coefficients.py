"""Report section: the paper's eqs 14-20, printed beside derived, and the errata table.

``measure`` is :func:`dispersion.claims.errata.paper_errata`: it verifies the claims file shipped
with the package (``dispersion/data/paper_claims.toml``) and builds the errata rows.
``render`` writes ``coefficients.md`` and ``coefficients.tex`` (a complete LaTeX document)
from the stored JSON alone. The stored result names the claims file by its place in the
package (``dispersion/data/paper_claims.toml``), never by a path of the measuring machine.

Everything here is exact algebra: a reproduction must give identical strings
(:data:`TOLERANCES`; only the seconds are timings).
"""
from __future__ import annotations

import dataclasses
from pathlib import Path

from dispersion.claims.errata import errata_document, format_table, paper_errata
from dispersion.io import write_text
from dispersion.report.compare import timing

__all__ = ["measure", "render", "summary", "headline", "TOLERANCES", "CLAIMS_FILE"]

#: The paper's claims file, named relative to the installed package's parent.
CLAIMS_FILE = "dispersion/data/paper_claims.toml"

#: Comparison rules (:mod:`dispersion.report.compare`): every other field identical.
TOLERANCES = (timing("seconds", "wall time of the verification"),)


def measure(quick: bool = False, executor=None):
    """:func:`~dispersion.claims.errata.paper_errata` with the claims file named as
    :data:`CLAIMS_FILE`, so the stored result holds no path of the machine that measured."""
    result = paper_errata(quick=quick, executor=executor)
    claims = tuple(dataclasses.replace(c, file=CLAIMS_FILE) for c in result.claims)
    return dataclasses.replace(result, claims_file=CLAIMS_FILE, claims=claims)


def _claims_table(claims: list[dict]) -> str:
    lines = ["| claim | source | model | printed | derived | status | difference |",
             "|---|---|---|---|---|---|---|"]
    for c in claims:
        cells = [c["name"], c["source"] or "", c["model"], f"`{c['printed']}`",
                 f"`{c['derived']}`", c["status"], c["difference"] or ""]
        lines.append("| " + " | ".join(x.replace("|", "\\|") for x in cells) + " |")
    return "\n".join(lines)


def _patches_text(claims: list[dict]) -> str:
    """The discrete patches the claims were verified on, as each claim's model states them."""
    models = dict.fromkeys(c["model"] for c in claims
                           if not c["model"].startswith("Rayleigh-Lamb"))
    if not models:
        return "Every claim is of the exact Rayleigh-Lamb equation."
    return "Discrete equations, each on the patch its claim names: " + "; ".join(models) + "."


def render(data: dict, out: Path) -> str:
    """Write ``coefficients.md`` and ``coefficients.tex`` from the measured JSON; return Markdown."""
    out = Path(out)
    claims, rows, eq13 = data["claims"], data["rows"], data["eq13"]
    failing = [c["name"] for c in claims if not c["passed"]]
    verdict = ("every claim holds as recorded" if not failing else
               "claims that do not hold as printed: " + ", ".join(failing))
    eq13_md = "\n".join(f"- {b}: standard `{s}`; printed `{p}`" for b, s, p in eq13)
    text = (
        "## Series coefficients, eqs 14-20: printed vs derived\n\n"
        f"The printed equations are the claims file `{data['claims_file']}` shipped with the "
        "package; each is derived again by power balance and compared exactly "
        f"(`dispersion verify --paper`: {verdict}). {_patches_text(claims)}\n\n"
        "### Claims\n\n" + _claims_table(claims) + "\n\n"
        "### Errata: printed vs derived, term by term\n\n" + format_table(rows, "markdown")
        + "\n\nEq (13): leading balance q0(w) for Omega^2 = w kappa^(2 sigma). The standard "
        "Rayleigh-Lamb form gives w = 2/(1-nu) (S0) and 2/(3(1-nu)) (A0); the printed form "
        "with (p^2 - q^2)^2 has no A0 root and an S0 root that is not the bar speed:\n\n"
        + eq13_md + "\n")
    write_text(out / "coefficients.md", text)
    write_text(out / "coefficients.tex", errata_document(rows, eq13))
    return text + ("\nFiles: [coefficients.md](coefficients.md), "
                   "[coefficients.tex](coefficients.tex) (standalone LaTeX), "
                   "[coefficients.json](coefficients.json).\n")


def summary(data: dict) -> str:
    """The README block: each claim of the paper's file with its status and the difference found."""
    lines = ["| claim | compared on | status | difference (printed vs derived) |",
             "|---|---|---|---|"]
    for c in data["claims"]:
        cells = [c["name"], c["model"], c["status"], c["difference"] or ""]
        lines.append("| " + " | ".join(x.replace("|", "\\|") for x in cells) + " |")
    return "\n".join(lines) + "\n"


def headline(data: dict) -> str:
    """One line for the console: the claims that differ from the derivation, and how.

    >>> headline({"claims": [
    ...     {"name": "eq 17", "status": "differs", "difference": "kappa^6: sign"},
    ...     {"name": "eq 18", "status": "holds", "difference": None}]})
    'Errata (coefficients.md): eq 17 (kappa^6: sign) differs from the derivation; 1 of 2 printed claims hold.'
    """
    claims = data["claims"]
    holds = sum(c["status"] == "holds" for c in claims)
    differ = [f"{c['name']} ({c['difference']})" if c.get("difference") else c["name"]
              for c in claims if c["status"] == "differs"]
    other = [f"{c['name']} {c['status']}" for c in claims
             if c["status"] not in ("holds", "differs")]
    found = []
    if differ:
        found.append(", ".join(differ) + (" differs" if len(differ) == 1 else " differ")
                     + " from the derivation")
    found += other
    if not found:
        found.append("none")
    return (f"Errata (coefficients.md): {'; '.join(found)}; {holds} of {len(claims)} "
            "printed claims hold.")
