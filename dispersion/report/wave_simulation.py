"""Report section: measured cost against measured accuracy of a simulated guided wave (issue 30).

``measure`` is :func:`dispersion.studies.wave_simulation.measure` (its size: the environment
variable ``DISPERSION_WAVE_SIMULATION_SIZE``, default ``default``; the page says which ran);
``render`` writes four figures and the tables from the stored JSON, computing nothing.
"""
from __future__ import annotations

from pathlib import Path

from dispersion.io import save_figure
from dispersion.report.compare import close, timing, unjudged
from dispersion.studies.wave_simulation import measure

__all__ = ["measure", "render", "TOLERANCES", "FIGURES"]

#: Comparison rules (:mod:`dispersion.report.compare`), first match wins. Wall times are
#: listed, never judged, and so is what is chosen by them (the front, the cheapest by measured
#: cost, the traces shown). The simulations are deterministic given the step, which is the
#: Lanczos maximum rounded up to six digits (the same on every machine unless it sits on a
#: rounding boundary): errors agree to round-off of the FFTs and the root solvers, 1e-9
#: relative (an arrival error of 1e-4 over a travel of 340 H/c_T is 0.03 time units).
TOLERANCES = (
    timing("points[].loop_seconds", "wall time"),
    timing("points[].seconds_per_step[]", "wall time"),
    timing("points[].setup_seconds", "wall time"),
    timing("points[].seconds_per_time", "wall time"),
    timing("verification.loop_seconds", "wall time"),
    timing("verification.seconds_per_step[]", "wall time"),
    timing("verification.setup_seconds", "wall time"),
    timing("verification.seconds_per_time", "wall time"),
    unjudged("points[].worker", "the process that ran the point"),
    unjudged("verification.worker", "the process that ran the point"),
    unjudged("workers", "how many processes ran the sweep: the executor's"),
    unjudged("front[]", "chosen by wall times"),
    unjudged("cheapest[].*", "chosen by wall times (the measured choice)"),
    unjudged("traces[].*", "chosen by wall times (the cheapest runs)"),
    close("points[].*", rel=1e-9, abs=1e-12, why="deterministic runs: FFT and root round-off"),
    close("verification.*", rel=1e-9, abs=1e-12, why="deterministic run"),
    close("prediction[].*", rel=1e-9, abs=1e-12, why="from the points"),
)

#: The figures the section writes.
FIGURES = ("wave_simulation_pareto.png", "wave_simulation_prediction.png",
           "wave_simulation_signals.png", "wave_simulation_costs.png")


def _pct(x, digits: int = 3) -> str:
    return "-" if x is None else f"{100 * x:+.{digits}g} %"


def _size(x, digits: int = 3) -> str:
    return "-" if x is None else f"{100 * x:.{digits}g} %"


def _work(x) -> str:
    return "-" if x is None else f"{x:.3g}"


def _seconds(c) -> str:
    return "-" if c["loop_seconds"] is None else format(c["loop_seconds"], ".3g")


def _run_name(c) -> str:
    if c["p"] is None:
        return "none within the sweep"
    note = " (a cancellation of errors)" if c.get("cancellation") else ""
    return f"p = {c['p']}, {c['mass']}, {c['elements_per_wavelength']:g} per wavelength{note}"


def _cheapest_table(data) -> str:
    rows = ["| mode | target | choice | cheapest by measured seconds | loop [s] | error | "
            "cheapest by today's modelled cost | loop [s] | error |",
            "|---|---|---|---|---|---|---|---|---|"]
    by = {(c["mode"], c["target"], c["by"], c.get("robust", False)): c
          for c in data["cheapest"]}
    for mode in data["size"]["modes"]:
        for t in data["targets"]:
            for robust in (False, True):
                m, d = by[(mode, t, "measured", robust)], by[(mode, t, "modelled", robust)]
                rows.append(f"| {mode} | {100 * t:g} % | {'converged' if robust else 'any'} | "
                            f"{_run_name(m)} | {_seconds(m)} | {_size(m['arrival_error'])} | "
                            f"{_run_name(d)} | {_seconds(d)} | {_size(d['arrival_error'])} |")
    return "\n".join(rows)


def _prediction_summary(data) -> str:
    pts = data["points"]
    lines = []
    names = []
    for v in data["prediction"]:
        if v["measure"] not in names:
            names.append(v["measure"])
    for name in names:
        vs = [v for v in data["prediction"] if v["measure"] == name]
        held = sum(v["holds"] for v in vs)
        lines.append(f"- **{name}**: the prediction holds for {held} of {len(vs)} measured runs.")
        reasons = {}
        for v in vs:
            if not v["holds"]:
                reasons.setdefault(v["reason"], []).append(v)
        for reason, group in sorted(reasons.items(), key=lambda kv: -len(kv[1])):
            where = ", ".join(
                f"p = {pts[v['index']]['p']} {pts[v['index']]['mass']} "
                f"N = {pts[v['index']]['elements_per_wavelength']:g} "
                f"({_pct(v['measured'])} vs {_pct(v['predicted'])})" for v in group[:6])
            more = f" and {len(group) - 6} more" if len(group) > 6 else ""
            lines.append(f"  - {len(group)} not: {reason}. Where: {where}{more}.")
    return "\n".join(lines)


def _points_table(data) -> str:
    rows = ["| mode | p | mass | N | n | DOFs | mass | steps | dt / dt_crit(mesh) | "
            "dt_crit mesh / Bloch | loop [s] | s per step (min-median-max) | memory [MB] | "
            "modelled DOFs/dt | modelled work/dt | peak arrival | energy arrival | "
            "predicted arrival | "
            "phase-velocity err. | predicted | L2 | failures |",
            "|" + "---|" * 22]
    for pt in data["points"]:
        sps = pt["seconds_per_step"]
        ratio = ("-" if pt["dt_bloch"] is None else f"{pt['dt_crit'] / pt['dt_bloch']:.4g}")
        rows.append(
            f"| {pt['mode']} | {pt['p']} | {pt['mass']} | {pt['elements_per_wavelength']:g} | "
            f"{pt['n']} | {pt['dofs']} | {pt['mass_kind']} | {pt['n_steps']} | "
            f"{pt['dt'] / pt['dt_crit']:.3g} | {ratio} | {pt['loop_seconds']:.3g} | "
            f"{sps[0]:.2e} / {sps[1]:.2e} / {sps[2]:.2e} | {pt['nbytes'] / 1e6:.3g} | "
            f"{pt['modelled_cost']:.3g} | {_work(pt['modelled_work'])} | "
            f"{_pct(pt['peak_arrival_error'])} | "
            f"{_pct(pt['energy_arrival_error'])} | {_pct(pt['predicted_arrival_error'])} | "
            f"{_pct(pt['phase_velocity_error'])} | {_pct(pt['predicted_phase_velocity_error'])} | "
            f"{pt['l2_error']:.3g} | {'; '.join(pt['failures']) or ''} |")
    return "\n".join(rows)


def render(data: dict, out: Path) -> str:
    """Figures and Markdown from the stored result of :func:`measure`."""
    from dispersion.plotting.wave_simulation import (plot_costs, plot_pareto, plot_prediction,
                                                     plot_signals)

    out = Path(out)
    mode = data["size"]["modes"][0]
    figures = (plot_pareto(data, mode), plot_prediction(data, mode), plot_signals(data),
               plot_costs(data))
    for name, fig in zip(FIGURES, figures):
        save_figure(fig, out / name, dpi=110)
    s, size = data["strip"], data["size"]
    v = data["verification"]
    if v is None:
        verification = "The verification run was refused (see the failures)."
    else:
        verification = (
            f"The reference is verified against a converged simulation (p = {v['p']}, "
            f"{v['mass']} mass, {v['elements_per_wavelength']:g} elements per wavelength, "
            f"{v['dt'] / v['dt_crit']:.2g} of the critical step): arrival-time error "
            f"{_pct(v['peak_arrival_error'])} (peak), {_pct(v['energy_arrival_error'])} "
            f"(energy; predicted {_pct(v['predicted_arrival_error'])}); phase-velocity error "
            f"{v['phase_velocity_error']:.4g}, predicted {v['predicted_phase_velocity_error']:.4g}"
            f"; L2 error {v['l2_error']:.3g}.")
    refused = "".join(f"\n- {r['mode']} p = {r['p']} {r['mass']}"
                      + (f" N = {r['elements_per_wavelength']:g}"
                         if r["elements_per_wavelength"] is not None else "")
                      + f": {r['reason']}" for r in data["refused"]) or " none."
    failures = "".join(f"\n- {f}" for f in data["failures"]) or " none."
    return (
        "## Measured cost against measured accuracy: a simulated guided wave\n\n"
        f"Size **{size['name']}** ({len(data['points'])} runs on {data['workers']} worker "
        f"process(es)): modes {', '.join(size['modes'])}, p = "
        f"{', '.join(map(str, size['degrees']))}, every registered mass rule "
        f"({', '.join(data['rules'])}), N = "
        f"{', '.join(format(x, 'g') for x in size['elements_per_wavelength'])} elements per "
        f"wavelength (upwards, stopping at the first run within {100 * min(data['targets']):g} "
        f"%; a run over {size['budget']:.3g} DOF-steps is not run and is listed). The full "
        "sweep of the issue (A0 too, N up to 32) is the size `full` "
        "(`DISPERSION_WAVE_SIMULATION_SIZE=full dispersion reproduce --sections "
        "wave_simulation`).\n\n"
        f"The scene: a plane-strain {s['material']} strip of thickness d = "
        f"{s['thickness_mm']:g} mm, a {s['cycles']}-cycle Hann-windowed tone burst of carrier "
        f"k H = {s['kappa_c']:g} on the exact branch applied at one end (S0: symmetric "
        f"traction along x; A0: antisymmetric along y), recorded on the mid-plane from "
        f"{s['reference_station']:g} wavelengths (the reference station) to {s['travel']:g} "
        "wavelengths further; B-splines of degree p along and through the strip, elements no "
        "longer than a wavelength over N in either direction; central differences at "
        f"{s['courant']:g} of the mesh's own critical step (Lanczos on the assembled strip; "
        "the toolkit's Bloch-patch step beside it in the table). The reference is the "
        "reference station's record continued by the exact Rayleigh-Lamb branch (modal "
        "synthesis: exact phase and group delay at every frequency of the band). "
        f"{verification}\n\n"
        "### The cheapest setting for a target accuracy\n\n"
        "Error: the arrival time after the travel, the larger of the envelope peak's and the "
        "envelope centroid's (energy) error; a run with a measurement failure meets no "
        "target. 'any': the cheapest run within the target; 'converged': the cheapest whose "
        "error is not a cancellation (the signed error keeps its sign from the next coarser "
        "N, and the next finer N does no worse). Cost: wall seconds of the explicit loop "
        "(median of five timed segments times the steps; every run simulates the same time). "
        f"Timed while {data['workers']} worker process(es) ran the sweep side by side (the "
        "machine is in the table at the end of the page): the seconds compare the runs of "
        "this sweep with each other; another machine gives other seconds.\n\n"
        + _cheapest_table(data) + "\n\n"
        "![measured Pareto front](wave_simulation_pareto.png)\n\n"
        "### Does the dispersion analysis predict the simulation?\n\n"
        "Prediction: the fully discrete branch of the Bloch plate patch with the run's "
        "thickness mesh, aspect ratio, rule and step (`dispersion.simulation."
        "dispersion_prediction`), at the burst's centre frequency (the group delay and phase of "
        "the carrier), and over the whole band: the energy centroid of a single mode travels "
        "exactly at its group delay averaged over its energy spectrum, so the branch's group "
        "velocity at every frequency, weighted by the spectrum the run received at the "
        "reference station, predicts the energy arrival. A prediction holds where the measured "
        f"error lies within {100 * data['prediction_rtol']:g} % of it (or "
        f"{data['prediction_atol']:g} absolute); the reasons below are stated rules applied "
        "to each run's own numbers.\n\n"
        + _prediction_summary(data) + "\n\n"
        "![predicted against measured](wave_simulation_prediction.png)\n\n"
        "### Signals\n\n![signals against the exact reference](wave_simulation_signals.png)\n\n"
        "### Measured cost against today's modelled cost\n\n"
        "The cost-accuracy chart models the cost as steps per unit time x DOFs x the rule's "
        "modelled work per DOF and step (a stiffness row plus a division, a banded product or "
        "a solve); the loop's seconds say what each step costs on this machine. Were the model "
        "right, every marker would lie on one line.\n\n"
        "![measured against modelled cost](wave_simulation_costs.png)\n\n"
        f"Not run:{refused}\n\nFailures of the study:{failures}\n\n"
        "<details><summary>Every run</summary>\n\n" + _points_table(data)
        + "\n\n</details>\n\n"
        "Data: `wave_simulation.json`. Regenerate: `dispersion reproduce --sections "
        "wave_simulation`.\n")
