"""Report section: exact orders of accuracy of every mass rule (issue 29).

``measure`` is :func:`dispersion.studies.lumping_orders.measure`; ``render`` writes the table
of leading error terms from the stored JSON alone (``lumping.md`` holds the coefficients).
Everything is exact algebra: a reproduction must give identical strings; only the seconds
are a timing.
"""
from __future__ import annotations

from pathlib import Path

from dispersion.io import write_text
from dispersion.report.compare import timing
from dispersion.studies.lumping_orders import measure

__all__ = ["measure", "render", "summary", "TOLERANCES"]

#: Comparison rules (:mod:`dispersion.report.compare`): every other field identical.
TOLERANCES = (timing("seconds", "wall time of the derivation"),)

_MODELS = (("bar", "theta"), ("plate S0", "kappa"), ("plate A0", "kappa"))


def _cell(row: dict, var: str) -> str:
    k = row["power"]
    text = f"beyond {var}^{row['consistent_power']}" if k is None else f"{var}^{k}"
    return text if row["keeps_order"] else f"**{text}** (lower)"


def render(data: dict, out: Path) -> str:
    """Markdown of the orders table (and ``lumping.md`` with every coefficient)."""
    out = Path(out)
    degrees = data["degrees"]
    by = {(r["rule"], r["p"], r["model"]): r for r in data["terms"]}
    parts = []
    for model, var in _MODELS:
        lines = [f"| rule | {' | '.join(f'p = {p}' for p in degrees)} |",
                 "|---|" + "---|" * len(degrees)]
        for rule in data["rules"]:
            cells = [(_cell(by[(rule, p, model)], var) if (rule, p, model) in by else "n/a")
                     for p in degrees]
            if any(c != "n/a" for c in cells):
                lines.append(f"| {rule} | {' | '.join(cells)} |")
        parts.append(f"**{model}**: power of the leading error term\n\n" + "\n".join(lines))
    keeps = [rule for rule in data["rules"]
             if all(r["keeps_order"] for r in data["terms"] if r["rule"] == rule)]
    info = ["| rule | what it is | explicit step (modelled) |", "|---|---|---|"]
    info += [f"| {name} | {desc} | {cost} |" for name, desc, cost in data["rule_info"]]
    detail = ["| rule | p | model | power | leading coefficient (exact) |", "|---|---|---|---|---|"]
    detail += [f"| {r['rule']} | {r['p']} | {r['model']} | {r['power']} | `{r['coefficient']}` |"
               for r in data["terms"]]
    write_text(out / "lumping.md", "# Leading error terms of the mass rules\n\n"
               + "\n".join(detail) + "\n")
    failures = "".join(f"- could not derive: {f}\n" for f in data.get("failures") or [])
    claims = ("### The papers' claims\n\n" + summary(data) + "\n") if data.get("literature") \
        else ""
    return (
        "## Orders of accuracy of the mass rules\n\n"
        f"Leading error term of each rule for p = {', '.join(map(str, degrees))}: the periodic "
        "bar (omega_h^2/omega^2 - 1 = c theta^k, theta = k h) and S0, A0 of the Bloch plate "
        f"patch ({data['plate_n']} control points through the thickness, r = b/H = "
        f"{data['plate_r']}; power-balance series to {data['series_order']} against the exact "
        "Rayleigh-Lamb series, exact in nu). A power in bold is lower than the consistent "
        "mass's at the same p: the rule loses the order. These are the periodic lattice's "
        "orders and modelled steps; a finite mesh's boundary rows add outliers and lower its "
        "step (section finite_patches). Rules that keep the order of the "
        f"consistent mass everywhere: {', '.join(keeps)}.\n\n"
        + "\n\n".join(parts) + "\n\n" + "\n".join(info) + "\n\n" + claims + failures
        + "Every coefficient: [lumping.md](lumping.md). Data: `lumping.json`. Regenerate: "
        "`dispersion reproduce --sections lumping`.\n")


def summary(data: dict) -> str:
    """The README block: each literature claim with its status and the difference found."""
    rows = data.get("literature") or []
    held = sum(1 for r in rows if r[3] in ("holds", "differs (expected)"))
    lines = [f"`dispersion verify examples/literature/*.toml`: {held} of {len(rows)} claims "
             "as recorded.", "",
             "| file | claim | status | difference (derived) |", "|---|---|---|---|"]
    for file, name, _source, status, diff in rows:
        cells = [file, name, status, diff]
        lines.append("| " + " | ".join(str(x).replace("|", "\\|") for x in cells) + " |")
    return "\n".join(lines) + "\n"
