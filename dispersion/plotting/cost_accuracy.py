"""Cost-accuracy chart of mass rules (:mod:`dispersion.studies.cost_accuracy`), from stored data."""
from __future__ import annotations

from dispersion.plotting import axes

__all__ = ["plot_cost_accuracy"]

_MARKERS = "osD^v<>pPX*hH8d"


def plot_cost_accuracy(data: dict, ax=None):
    """Worse of the S0/A0 phase-velocity errors against cost, one marker per rule, one colour
    per degree, the Pareto front as a step line. ``data`` is the stored result (plain JSON)."""
    ax = axes(ax, size=(7.5, 5.0))
    points = data["points"]
    rules = list(data["rules"])
    degrees = list(data["degrees"])
    colours = {p: f"C{i}" for i, p in enumerate(degrees)}
    for pt in points:
        err = max(abs(pt["error_S0"]), abs(pt["error_A0"]))
        ax.scatter(pt["cost"], err, marker=_MARKERS[rules.index(pt["mass"]) % len(_MARKERS)],
                   s=64 if pt["pareto"] else 30, color=colours[pt["p"]],
                   edgecolor="k" if pt["pareto"] else "none", zorder=3)
    front = sorted((pt["cost"], max(abs(pt["error_S0"]), abs(pt["error_A0"])))
                   for pt in points if pt["pareto"])
    if front:
        xs, ys = zip(*front)
        ax.step(xs, ys, where="post", color="k", lw=1, ls="--", zorder=2, label="Pareto front")
    for p in degrees:
        ax.scatter([], [], color=colours[p], marker="s", label=f"p = {p}")
    for i, rule in enumerate(rules):
        ax.scatter([], [], color="0.4", marker=_MARKERS[i % len(_MARKERS)], label=rule)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("modelled cost: steps per unit time x DOFs per unit area x work per DOF")
    ax.set_ylabel("phase-velocity error, worse of S0 and A0")
    ax.set_title(f"central differences at {data['courant']:g} x the critical step, "
                 f"{data['elements_per_wavelength']} elements per wavelength, "
                 f"nu = {data['nu']:g}", fontsize="small")
    ax.legend(fontsize="x-small", ncol=2)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    return ax.figure
