"""Figures of the guided-wave simulation study (:mod:`dispersion.studies.wave_simulation`),
drawn from its stored result (plain JSON) alone: the measured Pareto front, the prediction of
the dispersion analysis against the measurement, the signals against their exact reference,
and the measured cost against today's modelled cost; and the figure of one run
(:func:`plot_run`, ``dispersion simulate --figure``).
"""
from __future__ import annotations

from dispersion.plotting import axes, new_figure

__all__ = ["plot_pareto", "plot_prediction", "plot_signals", "plot_costs", "plot_run"]

_MARKERS = "osD^v<>pPX*h"


def _style(data):
    from matplotlib import colormaps

    rules = list(data["rules"])
    degrees = sorted({pt["p"] for pt in data["points"]})
    palette = colormaps["tab10" if len(rules) <= 10 else "tab20"]
    colours = {rule: palette(i % palette.N) for i, rule in enumerate(rules)}
    markers = {p: _MARKERS[i % len(_MARKERS)] for i, p in enumerate(degrees)}
    return rules, degrees, colours, markers


def _handles(data):
    from matplotlib.lines import Line2D

    rules, degrees, colours, markers = _style(data)
    return ([Line2D([], [], ls="", marker="s", color=colours[r], label=r) for r in rules]
            + [Line2D([], [], ls="", marker=markers[p], color="0.4", label=f"p = {p}")
               for p in degrees])


def _legend(ax, data, where="lower left"):
    ax.legend(handles=_handles(data) + ax.get_legend_handles_labels()[0],
              fontsize="x-small", ncol=2, loc=where)


def plot_pareto(data: dict, mode: str = "S0", ax=None):
    """Loop seconds against the arrival-time error after the travel, every run (the bar: the
    fastest and slowest of its five timed segments); the measured Pareto front as a step line;
    the targets as horizontal lines; failed runs hollow."""
    ax = axes(ax, size=(7.5, 5.2))
    _, _, colours, markers = _style(data)
    pts = data["points"]
    for pt in pts:
        if pt["mode"] != mode or pt["arrival_error"] is None:
            continue
        ok = not pt["failures"]
        lo, _, hi = (v * pt["n_steps"] for v in pt["seconds_per_step"])
        ax.errorbar(pt["loop_seconds"], pt["arrival_error"],
                    xerr=[[pt["loop_seconds"] - lo], [hi - pt["loop_seconds"]]],
                    color=colours[pt["mass"]], lw=0.6, zorder=2)
        ax.scatter(pt["loop_seconds"], pt["arrival_error"], marker=markers[pt["p"]], s=34,
                   facecolor=colours[pt["mass"]] if ok else "none",
                   edgecolor=colours[pt["mass"]], lw=1.0, zorder=3)
    front = sorted((pts[i]["loop_seconds"], pts[i]["arrival_error"]) for i in data["front"]
                   if pts[i]["mode"] == mode)
    if front:
        xs, ys = zip(*front)
        ax.step(xs, ys, where="post", color="k", lw=1.0, ls="--", zorder=2,
                label="measured Pareto front")
    for t in data["targets"]:
        ax.axhline(t, color="0.5", lw=0.8, ls=":")
        ax.annotate(f"target {100 * t:g} %", (1.0, t), xycoords=("axes fraction", "data"),
                    ha="right", va="bottom", fontsize="x-small", color="0.3")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("measured cost: wall seconds of the explicit loop (the same simulated "
                  "time)\nbar: the spread of its five timed segments")
    ax.set_ylabel("arrival-time error after the travel (larger of peak and energy)")
    s = data["strip"]
    ax.set_title(f"{mode}: {s['cycles']}-cycle burst, kappa_c = {s['kappa_c']:g}, "
                 f"{s['travel']:g} wavelengths, central differences at {s['courant']:g} x "
                 "the critical step\nhollow: a failure at the far station (not measurable, "
                 "meets no target)", fontsize="small")
    _legend(ax, data)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    return ax.figure


def _pairs(data, mode, measured, predicted):
    out = []
    for pt in data["points"]:
        if pt["mode"] != mode or pt["failures"] or pt[predicted] is None or pt[measured] is None:
            continue
        out.append((pt, pt[predicted], pt[measured]))
    return out


def plot_prediction(data: dict, mode: str = "S0"):
    """Predicted (fully discrete branch) against measured: arrival time at the carrier
    (envelope peak hollow, energy centroid filled), energy arrival over the band, phase
    velocity; the diagonal and the band within which the prediction is said to hold."""
    import numpy as np

    fig = new_figure(figsize=(15.0, 6.0))
    left, middle, right = fig.subplots(1, 3)
    _, _, colours, markers = _style(data)
    rtol, atol = data["prediction_rtol"], data["prediction_atol"]
    panels = ((left, ("peak_arrival_error", "energy_arrival_error"), "predicted_arrival_error",
               "arrival-time error", "the carrier"),
              (middle, ("energy_arrival_error",), "predicted_band_arrival_error",
               "energy arrival-time error", "the band"),
              (right, ("phase_velocity_error",), "predicted_phase_velocity_error",
               "phase-velocity error", "the carrier"))
    for ax, measured, predicted, what, where in panels:
        lo, hi = np.inf, 0.0
        for k, m in enumerate(measured):
            for pt, x, y in _pairs(data, mode, m, predicted):
                face = colours[pt["mass"]] if k == len(measured) - 1 else "none"
                ax.scatter(abs(x), abs(y), marker=markers[pt["p"]], s=30, facecolor=face,
                           edgecolor=colours[pt["mass"]], lw=0.9, zorder=3)
                if x * y < 0:  # opposite signs: a cross through the marker
                    ax.scatter(abs(x), abs(y), marker="x", s=16, color="k", lw=0.7, zorder=4)
                lo, hi = min(lo, abs(x), abs(y)), max(hi, abs(x), abs(y))
        if hi > 0:
            lo = max(lo, 1e-8)
            grid = np.geomspace(lo / 2, hi * 2, 50)
            ax.plot(grid, grid, color="k", lw=0.8)
            width = np.maximum(rtol * grid, atol)
            ax.fill_between(grid, np.maximum(grid - width, lo / 3), grid + width,
                            color="0.85", zorder=1, label=f"holds: within {100 * rtol:g} % "
                            f"or {atol:g}")
            ax.set_ylim(lo / 3, hi * 3)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(f"predicted {what}\n(fully discrete branch over {where})")
        ax.set_ylabel(f"measured {what}")
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
    left.set_title("arrival time against the carrier's group delay\nhollow = envelope peak, "
                   "filled = energy centroid; x = opposite sign", fontsize="small")
    middle.set_title("energy arrival against the group delay averaged over\nthe burst's "
                     "spectrum at the reference station", fontsize="small")
    right.set_title("phase velocity of the carrier over the travel", fontsize="small")
    right.legend(fontsize="x-small", loc="upper left")
    fig.legend(handles=_handles(data), loc="outside lower center", ncol=10,
               fontsize="x-small")
    fig.suptitle(f"{mode}: what the dispersion analysis predicted against what the simulation "
                 "measured", fontsize="medium")
    return fig


def plot_signals(data: dict):
    """Each stored trace: the simulated far-station signal over its exact reference."""
    traces = data["traces"]
    fig = new_figure(figsize=(10.0, 2.1 * max(len(traces), 1) + 0.6))
    axs = fig.subplots(max(len(traces), 1), 1, squeeze=False)[:, 0]
    s = data["strip"]
    for ax, tr in zip(axs, traces):
        ax.plot(tr["t"], tr["reference"], color="k", lw=1.6, label="exact reference")
        ax.plot(tr["t"], tr["simulated"], color="C3", lw=0.9, label="simulated")
        ax.set_title(f"{tr['why']}: {tr['mode']}, p = {tr['p']}, {tr['mass']} mass, "
                     f"{tr['elements_per_wavelength']:g} elements per wavelength, courant "
                     f"{tr['courant']:g}; arrival-time error {100 * tr['arrival_error']:.3g} %",
                     fontsize="small")
        ax.set_ylabel("v at the far station [c_T]", fontsize="small")
        ax.grid(True, lw=0.3, alpha=0.5)
    axs[0].legend(fontsize="x-small", loc="upper right")
    axs[-1].set_xlabel("t [H / c_T]")
    fig.suptitle(f"received bursts after {s['travel']:g} wavelengths against the exact "
                 "modal synthesis", fontsize="medium")
    return fig


def plot_costs(data: dict, ax=None):
    """Measured wall seconds per simulated time against today's modelled cost (steps per unit
    time x DOFs x the rule's modelled work per DOF): filled = diagonal mass (a division),
    hollow = any other step (a solve, a banded or a dense product)."""
    ax = axes(ax, size=(7.0, 5.0))
    _, _, colours, markers = _style(data)
    for pt in data["points"]:
        diag = pt["mass_kind"] == "diagonal"
        if pt.get("modelled_work") is None:
            continue
        ax.scatter(pt["modelled_work"], pt["seconds_per_time"], marker=markers[pt["p"]], s=30,
                   facecolor=colours[pt["mass"]] if diag else "none",
                   edgecolor=colours[pt["mass"]], lw=0.9)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("modelled cost of today's chart: DOFs x work per DOF / dt  "
                  "[multiply-adds per H/c_T]")
    ax.set_ylabel("measured: wall seconds of the loop per H/c_T simulated")
    ax.set_title("filled: a division per DOF; hollow: a solve, a banded or a dense product\n"
                 "a right model would put every marker on one line", fontsize="small")
    _legend(ax, data, "upper left")
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    return ax.figure


def plot_run(run):
    """One :class:`dispersion.simulation.wave_run.WaveRun`: every station's record over its
    reference, offset by distance."""
    import numpy as np

    fig = new_figure(figsize=(10.0, 6.0))
    ax = fig.add_subplot()
    t = run.times
    x = np.asarray(run.plan.stations) / run.plan.wavelength
    scale = 0.45 * (x[1] - x[0]) / max(float(np.abs(run.records).max()), 1e-300)
    for s in range(len(x)):
        ax.plot(t, x[s] + scale * run.reference[:, s], color="k", lw=1.4,
                label="exact reference" if s == 0 else None)
        ax.plot(t, x[s] + scale * run.records[:, s], color="C3", lw=0.8,
                label="simulated" if s == 0 else None)
    ax.set_xlabel("t [H / c_T]")
    ax.set_ylabel("station [wavelengths from the loaded end]")
    ax.set_title(run.title() + "\narrival-time error at the far station "
                 f"{100 * run.far.arrival_error:+.3g} % (peak), "
                 f"{100 * run.far.energy_arrival_error:+.3g} % (energy)", fontsize="small")
    ax.legend(fontsize="x-small", loc="lower right")
    ax.grid(True, lw=0.3, alpha=0.5)
    return fig
