"""Speed charts of the series engine (data of :func:`dispersion.studies.series_race.measure`).

>>> fig = plot_race([{"order": 8, "ours_process_s": 0.3, "ours_compute_s": 0.01,
...                   "maxima_process_s": 0.2, "maxima_compute_s": 0.03}])
>>> fig.axes[0].get_ylabel()
'seconds (S0 + A0, nu symbolic)'
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence

from dispersion.plotting import axes
from dispersion.plotting.styles import mass_style

__all__ = ["plot_race", "plot_scaling"]

_RACE = (("ours_process_s", "ours, whole process (cold)", "C0", "o", "-"),
         ("ours_lean_process_s", "ours, lean entry (no sympy import)", "C9", "D", "--"),
         ("maxima_process_s", "Maxima, whole process (cold)", "C2", "s", "-"),
         ("ours_compute_s", "ours, compute only", "C0", "o", ":"),
         ("maxima_compute_s", "Maxima, compute only (its own timer)", "C2", "s", ":"))
_DEGREE = {2: ("o", "-"), 3: ("s", "--"), 4: ("^", ":")}


def plot_race(race: Sequence[Mapping], ax=None):
    """Seconds to the S0 + A0 series against the highest power of kappa, ours and Maxima."""
    ax = axes(ax, (5.5, 4.0))
    for key, label, color, marker, line in _RACE:
        pts = [(p["order"], p[key]) for p in race if p.get(key)]
        if pts:
            k, s = zip(*pts)
            ax.plot(k, s, color=color, marker=marker, linestyle=line, label=label)
    ax.set_yscale("log")
    ax.set_xlabel("highest power of $\\kappa$ (exact Rayleigh-Lamb series)")
    ax.set_ylabel("seconds (S0 + A0, nu symbolic)")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize="small")
    return ax.figure


def plot_scaling(points: Sequence[Mapping], fits: Sequence[Mapping] = (), ax=None):
    """Seconds of the discrete S0 + A0 series against n, per mass and degree (log-log)."""
    ax = axes(ax, (5.5, 4.0))
    exponent = {(f["mass"], f["p"]): f["exponent"] for f in fits}
    for (mass, p) in sorted({(q["mass"], q["p"]) for q in points}):
        pts = sorted((q["n"], q["seconds"]) for q in points if q["mass"] == mass and q["p"] == p)
        n, s = zip(*pts)
        marker, line = _DEGREE.get(p, ("x", "-."))
        fit = exponent.get((mass, p))
        label = f"{mass}, p = {p}" + (f" (t ~ n^{fit:.1f})" if fit is not None else "")
        ax.plot(n, s, color=mass_style(mass).colour, marker=marker, linestyle=line, label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ns = sorted({q["n"] for q in points})
    ax.set_xticks(ns, [str(v) for v in ns])
    ax.minorticks_off()
    order = points[0]["order"] if points else None
    ax.set_xlabel("control points n through the thickness")
    ax.set_ylabel(f"seconds (S0 + A0 to $\\kappa^{{{order}}}$)")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize="x-small", ncol=1)
    return ax.figure
