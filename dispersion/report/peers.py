"""Report section: the Lamb-wave calculators on the package index, side by side with ours.

``measure`` is :func:`dispersion.studies.peers.measure`; ``render`` writes the Markdown
table from the stored JSON. Peers that are not installed are listed as skipped, peers that
failed as failed (never timed).
"""
from __future__ import annotations

from pathlib import Path

from dispersion.report.compare import Peer, close, machine, timing
from dispersion.studies.peers import PEERS_INSTALL, TOOLS, measure

__all__ = ["measure", "render", "render_tables", "missing_peers", "TOLERANCES"]

#: Comparison rules (:mod:`dispersion.report.compare`), first match wins. Times are listed,
#: never judged; the peers are an optional extra (installed or not on the machine that
#: reproduces), so only our own row is judged: the roots we find exactly, their errors to
#: 1e-12. The reference roots are the union of every installed tool's roots, so their count
#: (and the count of ours missed among them) depends on which peers the machine has.
TOLERANCES = (
    timing("*.seconds", "wall time"),
    timing("*.time_over_ours", "ratio of wall times"),
    close("tasks.*.tools.dispersion.*_error", abs=1e-12,
          why="round-off of the root solver and of the mpmath reference"),
    close("curves.*", rel=1e-12, why="our branches in physical units: roots certified to 1e-12"),
    machine("tasks.*.reference roots", "the union of the installed tools' roots"),
    machine("tasks.*.tools.dispersion.missed", "counted against the installed tools' roots"),
    machine("tasks.*.tools.disba.*", "optional peer (the peers extra): installed or not"),
    machine("tasks.*.tools.displam.*", "optional peer (the peers extra): installed or not"),
    machine("tasks.*.tools.lambwaves.*", "optional peer: not on the package index"),
    machine("python", "Python version of the machine"),
)


def missing_peers(data: dict) -> tuple[Peer, ...]:
    """The peers of :data:`~dispersion.studies.peers.TOOLS` the stored result shows were not
    installed (one line for all) or failed (one line each).

    >>> row = {"tools": {"dispersion": {"status": "ok"}, "disba": {"status": "not installed"},
    ...                  "displam": {"status": "not installed"}}}
    >>> missing_peers({"tasks": {"branches": row}})[0].line()
    'disba, displam not installed: side-by-side runs not run; pip install -e ".[peers]"'
    """
    status = {}
    for task in data.get("tasks", {}).values():
        for tool, row in task["tools"].items():
            if tool != TOOLS[0] and row["status"] != "ok":
                status.setdefault(tool, row["status"])
    absent = [t for t, s in status.items() if s == "not installed"]
    out = [Peer(", ".join(absent), "not installed", "side-by-side runs not run",
                PEERS_INSTALL)] if absent else []
    out += [Peer(t, "failed", "not timed (peers section)", f"its message: {s.removeprefix('failed: ')}")
            for t, s in status.items() if s != "not installed"]
    return tuple(out)

_HEAD = ("| task | tool | status | reference roots | found | missed | spurious | "
         "max rel. error | median rel. error | whole process [s] | time / ours |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|\n")


def _f(x, digits: int = 2) -> str:
    return "-" if x is None else f"{x:.{digits}g}"


def render_tables(data: dict) -> str:
    """The Markdown table of every task and tool (no recomputation)."""
    lines = []
    for task in data["tasks"].values():
        for tool, row in task["tools"].items():
            ok = row["status"] == "ok"
            lines.append(
                f"| {task['name']} ({task['frequencies']} frequencies) | {tool} | "
                f"{row['status']} | {task['reference roots']} | "
                + " | ".join(str(row[k]) if ok else "-" for k in ("found", "missed", "spurious"))
                + f" | {_f(row.get('max_error'))} | {_f(row.get('median_error'))} | "
                f"{_f(row.get('seconds'), 3)} | {_f(row.get('time_over_ours'), 3)} |")
    return _HEAD + "\n".join(lines) + "\n"


def summary(data: dict) -> str:
    """One line per task: who found every reference root, and the time ratios."""
    out = []
    for task in data["tasks"].values():
        parts = []
        for tool, row in task["tools"].items():
            if row["status"] != "ok":
                parts.append(f"{tool} {row['status']}")
                continue
            parts.append(f"{tool} {row['found']}/{task['reference roots']} roots, max error "
                         f"{_f(row['max_error'])}, time/ours {_f(row['time_over_ours'], 3)}")
        out.append(f"- {task['name']}: " + "; ".join(parts) + ".")
    return "\n".join(out) + "\n"


#: The figure of our modes of the benchmark plate (README links it).
FIGURE = "lamb_aluminium.png"


def render(data: dict, out: Path) -> str:
    """Markdown of the section, and the figure of our modes, from the stored result."""
    import numpy as np

    from dispersion.io import save_figure
    from dispersion.plotting.lamb import figure_dispersion

    c = data["curves"]
    modes = {lab: {k: np.array([np.nan if x is None else x for x in v], dtype=float)
                   for k, v in d.items()} for lab, d in c["modes"].items()}
    fig = figure_dispersion(modes, c["title"], c["zgv"], c["cutoffs [kHz]"])
    save_figure(fig, Path(out) / FIGURE, dpi=130)
    m = data["material"]
    return (
        "## Side by side: Lamb-wave calculators from the package index\n\n"
        f"![Lamb and SH modes of the benchmark plate]({FIGURE})\n\n"
        f"Plate: c_L = {m['c_L [m/s]']:g} m/s, c_T = {m['c_T [m/s]']:g} m/s, "
        f"d = {m['thickness [mm]']:g} mm. Each tool runs as a whole process in the same "
        "session (best of the repeats); reference roots are the textbook Rayleigh-Lamb "
        "equations solved by mpmath at 40 digits from every root any tool found; a root is "
        "found within 1e-2 in phase velocity (window 0.1-30 km/s). The machine may have been "
        f"shared: compare ratios, not seconds (Python {data['python']}).\n\n"
        + summary(data) + "\n" + render_tables(data))
