"""Report section: speed of the series engine against Maxima and the textbook sympy route.

Writes ``series_speed.png`` (seconds to reach each order of kappa, per route) and
``series_speed.json`` (the measured points) into ``out``.
"""
from __future__ import annotations

import json
from pathlib import Path

from ..benchmarking import order_sweep
from ..io import save_figure, write_text

__all__ = ["report"]


def report(out: Path, quick: bool = False, executor=None) -> str:
    """Run :func:`dispersion.benchmarking.order_sweep`, chart it, return the Markdown section.

    ``executor`` is not used: the timings run one after the other so that they do not compete
    for the cores.
    """
    from matplotlib.figure import Figure

    from ..plotting.speed import plot_time_vs_order

    out = Path(out)
    data = order_sweep(quick)
    fig = Figure(figsize=(10, 4), layout="constrained")
    a1, a2 = fig.subplots(1, 2)
    plot_time_vs_order(data["rayleigh_lamb"], a1, budget=data["budget_s"],
                       title="exact Rayleigh-Lamb S0 + A0 series, symbolic nu")
    plot_time_vs_order(data["cmm"], a2, budget=data["budget_s"],
                       title=f"plate patch p = 2, n = 3, CMM, {data['model']} r = {data['r']}")
    save_figure(fig, out / "series_speed.png", dpi=130)
    write_text(out / "series_speed.json", json.dumps(data, indent=1) + "\n")

    def last(points):
        return f"kappa^{points[-1][0]} in {points[-1][1]:.3g} s" if points else "no order"

    rl, cmm = data["rayleigh_lamb"], data["cmm"]
    notes = "".join(f"- {n}\n" for n in data["notes"])
    return (
        "## Speed of the series engine\n\n"
        "![series speed](series_speed.png)\n\n"
        "Seconds to derive the S0 and A0 series up to each power of kappa, with nu symbolic. "
        f"Rayleigh-Lamb: ours {last(rl['ours'])}, Maxima (`taylor`, wall time with start-up) "
        f"{last(rl['maxima'])}, textbook sympy `series` + `solve` {last(rl['textbook'])}. "
        f"Plate patch with CMM: ours {last(cmm['ours'])}, textbook `Matrix.det` + `series` "
        f"{last(cmm['textbook'])}. The textbook route was stopped after "
        f"{data['budget_s']:g} s per branch. Data: [series_speed.json](series_speed.json). "
        "The full table with ratios: `dispersion bench --out DIR`.\n\n"
        + (f"Notes:\n\n{notes}" if notes else "")
    )
