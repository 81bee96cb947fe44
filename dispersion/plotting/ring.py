"""Figures of the ring benchmark and the bar validation (:mod:`dispersion.contact`).

``plot_*`` take results and ``ax=None`` and return the Axes; :func:`figure4` lays out the
paper's Figure 4 (lumped above, singular below) on a pyplot-free Figure.

>>> ax = plot_energy_runtime([{"mass": "lumped", "dt": 0.05, "runtime": 1.0,
...                            "energy_change_percent": -5.0}])
>>> ax.get_xlabel()
'runtime per run (s)'
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from . import axes

__all__ = [
    "figure4",
    "plot_bar_force",
    "plot_bar_validation",
    "plot_contact_energy",
    "plot_energy_runtime",
]


def _axes(ax):
    return axes(ax, (6.0, 3.2))


def plot_contact_energy(result, ax=None, title: str | None = None):
    """Contact force (left axis) and total energy (right axis) of one ring run."""
    ax = _axes(ax)
    s = result.series
    ax.plot(s["t"], s["contact_force"], color="C0", lw=1.2, label="contact force")
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("contact force (N/m)", color="C0")
    right = ax.twinx()
    right.plot(s["t"], s["total"], color="C3", lw=1.2, label="total energy")
    right.set_ylabel("total energy (J/m)", color="C3")
    hi = float(np.max(s["total"]))
    right.set_ylim(0, 1.15 * hi if hi > 0 else 1)
    ax.set_title(title or f"{result.mass} mass ({result.scheme}): energy change "
                 f"{result.summary['energy_change_percent']:+.2f} %", fontsize=9)
    return ax


def figure4(lumped, singular, t_max: float | None = None):
    """Paper Figure 4: contact force and total energy, lumped (above) and singular (below)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.5, 5.5), layout="constrained")
    axes = fig.subplots(2, 1, sharex=True)
    plot_contact_energy(lumped, axes[0])
    plot_contact_energy(singular, axes[1])
    if t_max is not None:
        axes[1].set_xlim(0, t_max)
    return fig


def plot_bar_validation(rows: Sequence[dict], key: str = "energy_change_percent", ax=None):
    """Bar impact errors against the number of elements, one line per mass variant."""
    ax = _axes(ax)
    for k, mass in enumerate(sorted({r["mass"] for r in rows})):
        sel = sorted((r for r in rows if r["mass"] == mass), key=lambda r: r["n_elements"])
        ax.loglog([r["n_elements"] for r in sel], [max(abs(r[key]), 1e-16) for r in sel],
                  "o-", color=f"C{k}", label=mass)
    ax.set_xlabel("elements (dt = 0.5 h / c)")
    ax.set_ylabel(f"|{key}|")
    ax.legend(fontsize=8)
    return ax


def plot_bar_force(results: dict, ax=None):
    """Contact stress history of the bar, normalized by the exact value rho c v0."""
    ax = _axes(ax)
    for k, (mass, res) in enumerate(results.items()):
        arr = res.history.arrays()
        ax.plot(arr["t"], arr["contact_force"] / res.exact["stress"], color=f"C{k}", lw=1,
                label=mass)
    ex = next(iter(results.values())).exact
    ax.plot([0, ex["duration"], ex["duration"]], [1, 1, 0], "k--", lw=1, label="exact")
    ax.set_xlabel("time t c / L")
    ax.set_ylabel(r"contact stress / $\rho c v_0$")
    ax.legend(fontsize=8)
    return ax


def plot_energy_runtime(rows: Sequence[dict], ax=None):
    """|energy change| (%) against runtime over a dt sweep, one line per mass variant."""
    ax = _axes(ax)
    for k, mass in enumerate(sorted({r["mass"] for r in rows})):
        sel = sorted((r for r in rows if r["mass"] == mass and np.isfinite(r["runtime"])),
                     key=lambda r: r["runtime"])
        x = [r["runtime"] for r in sel]
        y = [max(abs(r["energy_change_percent"]), 1e-6) for r in sel]
        ax.loglog(x, y, "o-", color=f"C{k}", label=mass)
        for r, xi, yi in zip(sel, x, y):
            ax.annotate(f"{r['dt']:g}", (xi, yi), fontsize=6, xytext=(2, 2),
                        textcoords="offset points")
    ax.set_xlabel("runtime per run (s)")
    ax.set_ylabel("|energy change| (%)")
    ax.legend(fontsize=8, title="labels: dt (s)", title_fontsize=7)
    return ax
