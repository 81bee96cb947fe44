"""Figures of the guided-wave simulation study (:mod:`dispersion.studies.wave_simulation`),
drawn from its stored result (plain JSON) alone: the measured Pareto front, the prediction of
the dispersion analysis against the measurement, space and time apart (each run beside its
semi-discrete twin), the signals against their exact reference, and the measured cost
against today's modelled cost; and the figure of one run
(:func:`plot_run`, ``dispersion simulate --figure``).
"""
from __future__ import annotations

from dispersion.plotting import axes, new_figure

__all__ = ["plot_pareto", "plot_prediction", "plot_signals", "plot_costs", "plot_run",
           "plot_split", "SPLIT_MEASURES", "trace_title"]

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


def _headline_words(data) -> str:
    """'the largest of arrival, phase and waveform', from the stored headline names."""
    names = [h[0] for h in data.get("headline", ())]
    return ("the largest of " + ", ".join(names[:-1]) + " and " + names[-1]) if names else ""


def plot_pareto(data: dict, mode: str = "S0", ax=None):
    """What a user pays (total seconds: setup and loop) against the run's error after the
    travel (the largest of its three measures), every measurable run (the bar: the fastest
    and slowest of the loop's five timed segments); the measured Pareto front as a step
    line; the targets as horizontal lines. Runs that cannot be measured are not on the error
    scale: they are drawn as crosses in a strip of their own above it."""
    ax = axes(ax, size=(7.5, 5.6))
    _, _, colours, markers = _style(data)
    pts = data["points"]
    failed = []
    for pt in pts:
        if pt["mode"] != mode:
            continue
        if pt["failures"] or pt["error"] is None:
            failed.append(pt)
            continue
        lo, _, hi = (v * pt["n_steps"] for v in pt["seconds_per_step"])
        x = pt["total_seconds"]
        setup = x - pt["loop_seconds"]
        bar = [[max(x - setup - lo, 0.0)], [max(setup + hi - x, 0.0)]]
        ax.errorbar(x, pt["error"], xerr=bar, color=colours[pt["mass"]], lw=0.6, zorder=2)
        ax.scatter(x, pt["error"], marker=markers[pt["p"]], s=34,
                   facecolor=colours[pt["mass"]], edgecolor=colours[pt["mass"]], lw=1.0,
                   zorder=3)
    front = sorted((pts[i]["total_seconds"], pts[i]["error"]) for i in data["front"]
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
    costs = [pt["total_seconds"] for pt in pts if pt["mode"] == mode and pt["total_seconds"] > 0]
    if costs:  # the failed runs' costs too: they are drawn in the strip above
        ax.set_xlim(min(costs) / 1.3, max(costs) * 1.3)
    strip = ax.inset_axes([0.0, 1.01, 1.0, 0.1])
    for pt in failed:
        strip.scatter(pt["total_seconds"], 0.3, marker="x", s=30, color=colours[pt["mass"]],
                      lw=1.0)
    strip.set_xscale("log")
    strip.set_xlim(ax.get_xlim())
    strip.set_ylim(0, 1)
    strip.set_yticks([])
    strip.tick_params(which="both", bottom=False, labelbottom=False)
    strip.set_facecolor("0.93")
    strip.text(0.005, 0.75, f"not measurable: {len(failed)} failed runs at their cost, no "
               "error to draw", transform=strip.transAxes, va="center", fontsize="x-small",
               color="0.25")
    ax.set_xlabel("what a user pays: wall seconds of the run (assembly, factorization, step "
                  "estimate and loop)\nbar: the spread of the loop's five timed segments")
    ax.set_ylabel(f"error after the travel: {_headline_words(data)}")
    s = data["strip"]
    strip.set_title(f"{mode}: {s['cycles']}-cycle burst, kappa_c = {s['kappa_c']:g}, "
                    f"{s['travel']:g} wavelengths, central differences at {s['courant']:g} x "
                    "the critical step", fontsize="small")
    _legend(ax, data)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    strip.set_xlim(ax.get_xlim())
    return ax.figure


#: The measures of the space/time figure: (field of the fully discrete run, its semi-discrete
#: twin, axis label).
SPLIT_MEASURES = (("phase_velocity_error", "semi_phase_velocity_error",
                   "|phase-velocity error| of the carrier"),
                  ("l2_error", "semi_l2_error", "relative L2 error of the received signal"))


def plot_split(data: dict, mode: str = "S0"):
    """Space and time apart: for every degree (columns) and rule (colours), the fully
    discrete error of each run (filled, solid) and its semi-discrete (space only) twin
    (hollow, dashed) against N, for the carrier's phase velocity and the waveform (rows);
    guide slopes N^-2 (what central differences add at a fixed Courant number) and N^-2p."""
    import numpy as np

    pts = [pt for pt in data["points"] if pt["mode"] == mode and not pt["failures"]]
    degrees = sorted({pt["p"] for pt in pts}) or [1]
    fig = new_figure(figsize=(3.4 * len(degrees) + 1.0, 7.4))
    grid = fig.subplots(len(SPLIT_MEASURES), len(degrees), squeeze=False, sharex=True,
                        sharey="row")
    _, _, colours, markers = _style(data)
    for col, p in enumerate(degrees):
        for row, (full, semi, label) in enumerate(SPLIT_MEASURES):
            ax = grid[row, col]
            values = []
            for mass in data["rules"]:
                line = sorted((pt for pt in pts if pt["p"] == p and pt["mass"] == mass),
                              key=lambda q: q["elements_per_wavelength"])
                for key, ls, face in ((full, "-", True), (semi, "--", False)):
                    xy = [(q["elements_per_wavelength"], abs(q[key])) for q in line
                          if q[key] is not None and q[key] != 0]
                    if not xy:
                        continue
                    x, y = zip(*xy)
                    values += y
                    ax.plot(x, y, ls=ls, lw=0.8, color=colours[mass],
                            marker=markers[p], ms=4.5,
                            mfc=colours[mass] if face else "none", mec=colours[mass])
            if values:
                n = np.array([3.5, 17.0])
                top = max(values)
                for k, ls in {2: ":", 2 * p: "-."}.items():
                    ax.plot(n, top * (n / n[0]) ** -k, color="0.35", lw=0.8, ls=ls)
                    ax.annotate(f"N^-{k}", (n[1], top * (n[1] / n[0]) ** -k), fontsize="x-small",
                                color="0.3", ha="left", va="center")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.grid(True, which="both", lw=0.3, alpha=0.5)
            if row == 0:
                ax.set_title(f"p = {p}", fontsize="small")
            if col == 0:
                ax.set_ylabel(label, fontsize="small")
            if row == len(SPLIT_MEASURES) - 1:
                ax.set_xlabel("N, elements per wavelength")
                ax.set_xticks([4, 6, 8, 12, 16], labels=["4", "6", "8", "12", "16"])
    from matplotlib.lines import Line2D

    handles = (_handles(data)[:len(data["rules"])]
               + [Line2D([], [], color="0.3", marker="o", label="fully discrete (the run)"),
                  Line2D([], [], color="0.3", ls="--", marker="o", mfc="none",
                         label="semi-discrete (space only)")])
    fig.legend(handles=handles, loc="outside lower center", ncol=8 if len(degrees) > 2 else 4,
               fontsize="x-small")
    s = data["strip"]
    fig.suptitle(f"{mode}: space and time apart after {s['travel']:g} wavelengths, central "
                 f"differences at {s['courant']:g} x the critical step", fontsize="medium")
    return fig


def _pairs(data, mode, measured, predicted):
    out = []
    for i, pt in enumerate(data["points"]):
        if pt["mode"] != mode or pt["failures"] or pt[predicted] is None or pt[measured] is None:
            continue
        out.append((i, pt, pt[predicted], pt[measured]))
    return out


#: The panels of :func:`plot_prediction`: (measured fields, predicted field, the verdict's
#: measure name for each measured field, what, over what).
_PANELS = ((("peak_arrival_error", "energy_arrival_error"), "predicted_arrival_error",
            ("envelope-peak arrival (carrier)", "energy arrival (carrier)"),
            "arrival-time error", "the carrier"),
           (("energy_arrival_error",), "predicted_band_arrival_error",
            ("energy arrival (band)",), "energy arrival-time error", "the band"),
           (("phase_velocity_error",), "predicted_phase_velocity_error",
            ("phase velocity (carrier)",), "phase-velocity error", "the carrier"))


def plot_prediction(data: dict, mode: str = "S0"):
    """Top: predicted (fully discrete branch) against measured: arrival time at the carrier
    (envelope peak hollow, energy centroid filled), energy arrival over the band, phase
    velocity, with the diagonal; a run whose prediction does not hold is ringed. Bottom: the
    test itself, each run's disagreement |measured - predicted| against its tolerance (the
    floor plus its own spreads), both relative to the prediction: below the diagonal the
    prediction holds."""
    import numpy as np

    fig = new_figure(figsize=(15.0, 10.5))
    grid = fig.subplots(2, 3)
    _, _, colours, markers = _style(data)
    verdicts = {(v["index"], v["measure"]): v for v in data["prediction"]}
    for col, (measured, predicted, names, what, where) in enumerate(_PANELS):
        ax, test = grid[0, col], grid[1, col]
        lo, hi = np.inf, 0.0
        tlo, thi = np.inf, 0.0
        for k, (m, name) in enumerate(zip(measured, names)):
            for i, pt, x, y in _pairs(data, mode, m, predicted):
                v = verdicts.get((i, name))
                face = colours[pt["mass"]] if k == len(measured) - 1 else "none"
                ax.scatter(abs(x), abs(y), marker=markers[pt["p"]], s=30, facecolor=face,
                           edgecolor=colours[pt["mass"]], lw=0.9, zorder=3)
                if v is not None and not v["holds"]:
                    ax.scatter(abs(x), abs(y), marker="o", s=90, facecolor="none",
                               edgecolor="k", lw=0.7, zorder=4)
                if x * y < 0:  # opposite signs: a cross through the marker
                    ax.scatter(abs(x), abs(y), marker="x", s=16, color="k", lw=0.7, zorder=4)
                lo, hi = min(lo, abs(x), abs(y)), max(hi, abs(x), abs(y))
                if v is not None and v["tolerance"] and x:
                    gap = max(abs(y - x), 1e-12 * abs(x)) / abs(x)
                    tol = v["tolerance"] / abs(x)
                    test.scatter(tol, gap, marker=markers[pt["p"]], s=30, facecolor=face,
                                 edgecolor=colours[pt["mass"]], lw=0.9, zorder=3)
                    tlo, thi = min(tlo, tol, gap), max(thi, tol, gap)
        if hi > 0:
            lo = max(lo, 1e-8)
            line = np.geomspace(lo / 2, hi * 2, 50)
            ax.plot(line, line, color="k", lw=0.8)
            ax.set_ylim(lo / 3, hi * 3)
        if thi > 0:
            tlo = max(tlo, 1e-12)
            line = np.geomspace(tlo / 2, thi * 2, 50)
            test.plot(line, line, color="k", lw=0.8)
            test.fill_between(line, tlo / 3, line, color="0.9", zorder=1)
            test.set_ylim(tlo / 3, thi * 3)
        for a in (ax, test):
            a.set_xscale("log")
            a.set_yscale("log")
            a.grid(True, which="both", lw=0.3, alpha=0.5)
        ax.set_xlabel(f"predicted {what}\n(fully discrete branch over {where})")
        ax.set_ylabel(f"measured {what}")
        test.set_xlabel("tolerance of the run / |predicted|\n(floor + the run's own spreads)")
        test.set_ylabel("|measured - predicted| / |predicted|")
    grid[0, 0].set_title("arrival time against the carrier's group delay\nhollow = envelope "
                         "peak, filled = energy centroid; x = opposite sign", fontsize="small")
    grid[0, 1].set_title("energy arrival against the group delay averaged over\nthe burst's "
                         "spectrum at the reference station", fontsize="small")
    grid[0, 2].set_title("phase velocity of the carrier over the travel", fontsize="small")
    for ax in grid[1]:
        ax.set_title("the test: below the diagonal the prediction holds", fontsize="small")
    from matplotlib.lines import Line2D

    grid[0, 2].legend(handles=[Line2D([], [], ls="", marker="o", mfc="none", mec="k", ms=9,
                                      label="the prediction does not hold")],
                      fontsize="x-small", loc="upper left")
    fig.legend(handles=_handles(data), loc="outside lower center", ncol=10,
               fontsize="x-small")
    fig.suptitle(f"{mode}: what the dispersion analysis predicted against what the simulation "
                 "measured", fontsize="medium")
    return fig


def trace_title(tr: dict) -> str:
    """A stored trace's title: what it is, and its three errors or why it has none."""
    what = (f"{tr['why']}: {tr['mode']}, p = {tr['p']}, {tr['mass']} mass, "
            f"{tr['elements_per_wavelength']:g} elements per wavelength, courant "
            f"{tr['courant']:g}")
    if tr.get("failure"):
        return f"{what}\nfailed, not measurable: {tr['failure']}"
    return (f"{what}\narrival {100 * tr['arrival_error']:.3g} %, phase "
            f"{tr['phase_error']:+.3g} rad, L2 {100 * tr['l2_error']:.3g} % (the largest: "
            f"{tr['error_kind']})")


def plot_signals(data: dict):
    """Each stored trace: the simulated far-station signal and its semi-discrete (space only)
    twin over the exact reference; a failed run is titled as failed, not by a number."""
    traces = data["traces"]
    fig = new_figure(figsize=(10.0, 2.5 * max(len(traces), 1) + 0.6))
    axs = fig.subplots(max(len(traces), 1), 1, squeeze=False)[:, 0]
    s = data["strip"]
    for ax, tr in zip(axs, traces):
        ax.plot(tr["t"], tr["reference"], color="k", lw=1.6, label="exact reference")
        if tr.get("semi") is not None:
            ax.plot(tr["t"], tr["semi"], color="C0", lw=0.9, ls="--",
                    label="semi-discrete (space only)")
        ax.plot(tr["t"], tr["simulated"], color="C3", lw=0.9, label="simulated")
        ax.set_title(trace_title(tr), fontsize="small")
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
    e = run.far
    if e.failure:
        words = f"far station: failed, not measurable: {e.failure}"
    else:
        phase = (f"phase {e.phase_error:+.3g} rad" if run.phase_certain
                 else "phase not followed")
        words = (f"at the far station: arrival {100 * e.arrival_error:+.3g} % (peak), "
                 f"{100 * e.energy_arrival_error:+.3g} % (energy); {phase}; "
                 f"L2 {100 * e.l2_error:.3g} %")
    ax.set_title(run.title() + "\n" + words, fontsize="small")
    ax.legend(fontsize="x-small", loc="lower right")
    ax.grid(True, lw=0.3, alpha=0.5)
    return fig
