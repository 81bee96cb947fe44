"""Speed charts of the series engine (:mod:`dispersion.benchmarking`).

>>> ax = plot_time_vs_order({"ours": [[4, 0.01], [8, 0.05]], "textbook": [[4, 3.0]]},
...                         budget=60.0)
>>> ax.get_ylabel()
'seconds (S0 + A0)'
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence

from . import axes

__all__ = ["plot_time_vs_order"]

_STYLE = {"ours": ("C0", "o", "-"), "maxima": ("C2", "s", "--"), "textbook": ("C3", "^", ":")}


def plot_time_vs_order(routes: Mapping[str, Sequence[Sequence[float]]], ax=None,
                       budget: float | None = None, title: str | None = None):
    """Seconds to reach each power of kappa, one line per route (log scale).

    A dotted line at ``budget`` marks where the textbook route was stopped: orders it did not
    reach took longer than that.
    """
    ax = axes(ax, (5.0, 3.8))
    for name, points in routes.items():
        color, marker, line = _STYLE.get(name, ("C7", "x", "-"))
        if points:
            k, s = zip(*points)
            ax.plot(k, s, color=color, marker=marker, linestyle=line, label=name)
        else:
            ax.plot([], [], color=color, marker=marker, linestyle=line,
                    label=f"{name} (no order within budget)")
    if budget is not None:
        ax.axhline(budget, color="C3", linewidth=0.8, linestyle=(0, (1, 3)),
                   label=f"textbook stopped at {budget:g} s per branch")
    ax.set_yscale("log")
    ax.xaxis.get_major_locator().set_params(integer=True)
    ax.set_xlabel("highest power of $\\kappa$ reached")
    ax.set_ylabel("seconds (S0 + A0)")
    if title:
        ax.set_title(title, fontsize="small")
    ax.legend(fontsize="small")
    return ax
