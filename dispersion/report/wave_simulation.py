"""Report section: measured cost against measured accuracy of a simulated guided wave (issue 30).

``measure`` is :func:`dispersion.studies.wave_simulation.measure` (its size: the environment
variable ``DISPERSION_WAVE_SIMULATION_SIZE``, default ``default``; the page says which ran);
``render`` writes five figures and the tables from the stored JSON, computing nothing.
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
    *(timing(f"{where}.{name}", "wall time") for where in ("points[]", "verification")
      for name in ("loop_seconds", "seconds_per_step[]", "setup_seconds", "seconds_per_time",
                   "assembly_seconds", "factorization_seconds", "step_seconds",
                   "bloch_seconds", "total_seconds")),
    timing("thickness[].seconds_per_step.*", "wall time"),
    unjudged("points[].worker", "the process that ran the point"),
    unjudged("verification.worker", "the process that ran the point"),
    unjudged("workers", "how many processes ran the sweep: the executor's"),
    unjudged("front[]", "chosen by wall times"),
    unjudged("cheapest[].*", "chosen by wall times (the measured choice)"),
    unjudged("traces[].*", "chosen by wall times (the cheapest runs)"),
    close("points[].*", rel=1e-9, abs=1e-12, why="deterministic runs: FFT and root round-off"),
    close("verification.*", rel=1e-9, abs=1e-12, why="deterministic run"),
    close("prediction[].*", rel=1e-9, abs=1e-12, why="from the points"),
    close("floors.*", rel=1e-9, abs=1e-12, why="from the verification run"),
)

#: The figures the section writes.
FIGURES = ("wave_simulation_pareto.png", "wave_simulation_split.png",
           "wave_simulation_prediction.png", "wave_simulation_signals.png",
           "wave_simulation_costs.png")


#: How the page names the timed steps of :data:`dispersion.simulation.wave_run.USER_PAYS`.
_PAYS_WORDS = {"critical_step": "the step estimate (Lanczos)", "loop": "the loop"}


def _pct(x, digits: int = 3) -> str:
    return "-" if x is None else f"{100 * x:+.{digits}g} %"


def _size(x, digits: int = 3) -> str:
    return "-" if x is None else f"{100 * x:.{digits}g} %"


def _rad(x) -> str:
    return "-" if x is None else f"{x:+.3g}"


def _work(x) -> str:
    return "-" if x is None else f"{x:.3g}"


def _secs(x) -> str:
    return "-" if x is None else f"{x:.3g}"


def _run_name(pt, note: str = "") -> str:
    return f"p = {pt['p']}, {pt['mass']}, {pt['elements_per_wavelength']:g} per wavelength{note}"


def _headline_words(data) -> str:
    names = [h[0] for h in data["headline"]]
    return ", ".join(names[:-1]) + " and " + names[-1]


def _errors(pt, semi: bool = False) -> str:
    """Three cells: arrival, phase [rad], L2 of a point (or of its semi-discrete twin); the
    largest in bold."""
    pre = "semi_" if semi else ""
    kind = pt[f"{pre}error_kind"]
    cells = {"arrival": _size(pt[f"{pre}arrival_error"]), "phase": _rad(pt[f"{pre}phase_error"]),
             "waveform": _size(pt[f"{pre}l2_error"])}
    if kind in cells:
        cells[kind] = f"**{cells[kind]}**"
    return " | ".join(cells[k] for k in ("arrival", "phase", "waveform"))


def _choice_row(data, mode, what, i, note="") -> str:
    if i is None:
        return f"| {mode} | {what} | none within the sweep | - | - | - | - | - | - | - | - |"
    pt = data["points"][i]
    return (f"| {mode} | {what} | {_run_name(pt, note)} | {_secs(pt['total_seconds'])} | "
            f"{_secs(pt['loop_seconds'])} | {_errors(pt)} | {_errors(pt, True)} |")


def _cheapest_table(data) -> str:
    rows = ["| mode | choice | run | total [s] | loop [s] | arrival | phase [rad] | L2 | "
            "space only: arrival | phase [rad] | L2 |", "|" + "---|" * 11]
    by = {(c["mode"], c["target"], c["by"], c["robust"]): c for c in data["cheapest"]}
    for mode in data["size"]["modes"]:
        for t in data["targets"]:
            for robust in (False, True):
                c = by[(mode, t, "measured", robust)]
                note = " (a cancellation of errors)" if c["cancellation"] else ""
                what = f"cheapest at {100 * t:g} % ({'converged' if robust else 'any'})"
                rows.append(_choice_row(data, mode, what, c["index"], note))
        rows.append(_choice_row(data, mode, "least error of the sweep", data["least"][mode]))
        rows.append(_choice_row(data, mode, "least space-only error of the sweep",
                                data["least_semi"][mode]))
    return "\n".join(rows)


def _modelled_table(data) -> str:
    rows = ["| mode | target | choice | cheapest by today's modelled cost | modelled work/dt | "
            "total [s] | arrival | phase [rad] | L2 | cheapest by total seconds | total [s] |",
            "|" + "---|" * 11]
    by = {(c["mode"], c["target"], c["by"], c["robust"]): c for c in data["cheapest"]}
    pts = data["points"]
    for mode in data["size"]["modes"]:
        for t in data["targets"]:
            for robust in (False, True):
                m, d = by[(mode, t, "measured", robust)], by[(mode, t, "modelled", robust)]
                if d["index"] is None:
                    modelled = "none within the sweep | - | - | - | - | -"
                else:
                    pt = pts[d["index"]]
                    modelled = (f"{_run_name(pt)} | {_work(pt['modelled_work'])} | "
                                f"{_secs(pt['total_seconds'])} | {_errors(pt)}")
                measured = ("none within the sweep | -" if m["index"] is None else
                            f"{_run_name(pts[m['index']])} | "
                            f"{_secs(pts[m['index']]['total_seconds'])}")
                rows.append(f"| {mode} | {100 * t:g} % | {'converged' if robust else 'any'} | "
                            f"{modelled} | {measured} |")
    return "\n".join(rows)


def _split_summary(data) -> str:
    """How many measurable runs meet each target in space alone and fully discrete."""
    pts = [pt for pt in data["points"] if not pt["failures"] and pt["error"] is not None]
    lines = []
    for t in data["targets"]:
        full = sum(pt["error"] <= t for pt in pts)
        space = sum(pt["semi_error"] is not None and pt["semi_error"] <= t for pt in pts)
        lines.append(f"- within {100 * t:g} %: {full} of the {len(pts)} measurable runs as "
                     f"run, {space} in space alone.")
    timed = [pt for pt in pts if pt["semi_phase_velocity_error"] is not None
             and pt["phase_velocity_error"] is not None]
    if timed:
        share = sorted(abs(pt["phase_velocity_error"] - pt["semi_phase_velocity_error"])
                       / max(abs(pt["phase_velocity_error"]), 1e-300) for pt in timed)
        lines.append(f"- the time integration's part of the phase-velocity error (run minus "
                     f"space only, over the run's): median {100 * share[len(share) // 2]:.3g} "
                     f"%, from {100 * share[0]:.3g} % to {100 * share[-1]:.3g} % over "
                     f"{len(timed)} runs.")
    return "\n".join(lines)


def _floors(data) -> str:
    return "; ".join(f"{name} {'-' if f is None else format(f, '.2g')}"
                     for name, f in data["floors"].items())


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
        tols = sorted(v["tolerance"] / abs(v["predicted"]) for v in vs
                      if v["tolerance"] is not None and v["predicted"])
        spread = (f" (tolerance {100 * tols[0]:.2g} % to {100 * tols[-1]:.2g} % of the "
                  f"prediction, median {100 * tols[len(tols) // 2]:.2g} %)" if tols else "")
        lines.append(f"- **{name}**: the prediction holds for {held} of {len(vs)} measured "
                     f"runs{spread}.")
        reasons = {}
        for v in vs:
            if not v["holds"]:
                reasons.setdefault(v["reason"], []).append(v)
        for reason, group in sorted(reasons.items(), key=lambda kv: -len(kv[1])):
            where = ", ".join(
                f"p = {pts[v['index']]['p']} {pts[v['index']]['mass']} "
                f"N = {pts[v['index']]['elements_per_wavelength']:g} "
                f"({_pct(v['measured'])} vs {_pct(v['predicted'])}"
                + ("" if v["tolerance"] is None else f", tolerance {v['tolerance']:.2g}") + ")"
                for v in group[:6])
            more = f" and {len(group) - 6} more" if len(group) > 6 else ""
            lines.append(f"  - {len(group)} not: {reason}. Where: {where}{more}.")
    return "\n".join(lines)


def _costs_summary(data) -> str:
    pts = data["points"]
    if not pts:
        return ""
    share = sorted(pt["setup_seconds"] / pt["total_seconds"] for pt in pts
                   if pt["total_seconds"] > 0)
    by_kind = {}
    for pt in pts:
        by_kind.setdefault(pt["mass_kind"], []).append(pt)
    parts = []
    for kind, group in sorted(by_kind.items()):
        f = max(pt["factorization_seconds"] for pt in group)
        st = max(pt["step_seconds"] for pt in group)
        a = max(pt["assembly_seconds"] for pt in group)
        parts.append(f"{kind} ({len(group)} runs): assembly up to {a:.3g} s, factorization up "
                     f"to {f:.3g} s, step estimate up to {st:.3g} s")
    return (f"The setup (assembly, factorization, step estimate) is {100 * share[0]:.2g} % to "
            f"{100 * share[-1]:.2g} % of the total seconds (median "
            f"{100 * share[len(share) // 2]:.2g} %); by the kind of mass: "
            + "; ".join(parts) + ".")


def _thickness_table(data) -> str:
    rows = ["| p | thickness elements | DOFs | lumped [s/step] | consistent [s/step] | "
            "consistent / lumped | consistent factor entries per point |", "|" + "---|" * 7]
    for tc in data["thickness"]:
        lum, con = tc["seconds_per_step"]["lumped"], tc["seconds_per_step"]["consistent"]
        fill = tc["factor_per_point"]["consistent"]
        for k, n_y in enumerate(tc["thickness_elements"]):
            own = " (the strip's)" if n_y == tc["plan_elements"] else ""
            rows.append(f"| {tc['strip']['p']} | {n_y}{own} | {tc['dofs'][k]} | "
                        f"{lum[k]:.3g} | {con[k]:.3g} | {con[k] / lum[k]:.3g} | "
                        f"{'-' if fill[k] is None else format(fill[k], '.3g')} |")
    return "\n".join(rows)


def _thickness_summary(data) -> str:
    out = []
    for tc in data["thickness"]:
        lum, con = tc["seconds_per_step"]["lumped"], tc["seconds_per_step"]["consistent"]
        fill = tc["factor_per_point"]["consistent"]
        n = tc["thickness_elements"]
        out.append(f"p = {tc['strip']['p']}: the consistent step costs {con[0] / lum[0]:.2g} "
                   f"lumped steps at {n[0]} elements through the thickness and "
                   f"{con[-1] / lum[-1]:.2g} at {n[-1]} (its factor {fill[0]:.3g} -> "
                   f"{fill[-1]:.3g} entries per point)")
    return "; ".join(out)


def _points_table(data) -> str:
    rows = ["| mode | p | mass | N | n | DOFs | mass | steps | dt / dt_crit(mesh) | "
            "dt_crit mesh / Bloch | assembly [s] | factorization [s] | step estimate [s] | "
            "loop [s] | total [s] | s per step (min-median-max) | memory [MB] | "
            "modelled DOFs/dt | modelled work/dt | peak arrival | energy arrival | "
            "predicted arrival | phase [rad] | phase-velocity err. | predicted | L2 | error | "
            "space only: arrival | phase [rad] | phase velocity | L2 | failures |",
            "|" + "---|" * 32]
    for pt in data["points"]:
        sps = pt["seconds_per_step"]
        ratio = ("-" if pt["dt_bloch"] is None else f"{pt['dt_crit'] / pt['dt_bloch']:.4g}")
        error = ("not measurable" if pt["error"] is None else
                 f"{_size(pt['error'])} ({pt['error_kind']})")
        failures = "; ".join(pt["failures"] + pt["semi_failures"])
        rows.append(
            f"| {pt['mode']} | {pt['p']} | {pt['mass']} | {pt['elements_per_wavelength']:g} | "
            f"{pt['n']} | {pt['dofs']} | {pt['mass_kind']} | {pt['n_steps']} | "
            f"{pt['dt'] / pt['dt_crit']:.3g} | {ratio} | {pt['assembly_seconds']:.3g} | "
            f"{pt['factorization_seconds']:.3g} | {pt['step_seconds']:.3g} | "
            f"{pt['loop_seconds']:.3g} | {pt['total_seconds']:.3g} | "
            f"{sps[0]:.2e} / {sps[1]:.2e} / {sps[2]:.2e} | {pt['nbytes'] / 1e6:.3g} | "
            f"{pt['modelled_cost']:.3g} | {_work(pt['modelled_work'])} | "
            f"{_pct(pt['peak_arrival_error'])} | "
            f"{_pct(pt['energy_arrival_error'])} | {_pct(pt['predicted_arrival_error'])} | "
            f"{_rad(pt['phase_error'])} | "
            f"{_pct(pt['phase_velocity_error'])} | {_pct(pt['predicted_phase_velocity_error'])} | "
            f"{pt['l2_error']:.3g} | {error} | {_size(pt['semi_arrival_error'])} | "
            f"{_rad(pt['semi_phase_error'])} | {_pct(pt['semi_phase_velocity_error'])} | "
            f"{_size(pt['semi_l2_error'])} | {failures} |")
    return "\n".join(rows)


def render(data: dict, out: Path) -> str:
    """Figures and Markdown from the stored result of :func:`measure`."""
    from dispersion.plotting.wave_simulation import (plot_costs, plot_pareto, plot_prediction,
                                                     plot_signals, plot_split)

    out = Path(out)
    mode = data["size"]["modes"][0]
    figures = (plot_pareto(data, mode), plot_split(data, mode), plot_prediction(data, mode),
               plot_signals(data), plot_costs(data))
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
            f"; L2 error {v['l2_error']:.3g} (space only: "
            f"{'-' if v['semi_l2_error'] is None else format(v['semi_l2_error'], '.3g')}).")
    refused = "".join(f"\n- {r['mode']} p = {r['p']} {r['mass']}"
                      + (f" N = {r['elements_per_wavelength']:g}"
                         if r["elements_per_wavelength"] is not None else "")
                      + f": {r['reason']}" for r in data["refused"]) or " none."
    failures = "".join(f"\n- {f}" for f in data["failures"]) or " none."
    pays = ", ".join(_PAYS_WORDS.get(k, k) for k in data["user_pays"])
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
        f"Error: the largest of three measures at the far station, {_headline_words(data)}: "
        "the arrival time (the larger of the envelope peak's and the envelope centroid's "
        "error, relative to the travel time), the carrier phase in radians (the relative L2 "
        "error a pure phase shift of the carrier makes) and the relative L2 error of the "
        "received signal; the largest is in bold. A run where one cannot be measured (a "
        "failure at the far station, or a carrier phase that cannot be followed) is not "
        "measurable and meets no target. 'any': the cheapest run within the target; "
        "'converged': the cheapest whose error is not a cancellation (neither the signed "
        "energy-arrival nor the phase error changes sign from the next coarser N, and the "
        "next finer N does no worse). 'Space only': the same three measures of the run's "
        "semi-discrete records, formed exactly from its own records by the frequency map of "
        "central differences (`dispersion.simulation.semi_discrete`): what the mesh does "
        "without the time integration. Cost: what a user pays, total wall seconds of "
        f"{pays} (the loop's: the median of five timed segments times the steps; every run "
        "simulates the same time); not counted: the plan (the exact roots of the scene, the "
        "same for every run), the toolkit's Bloch-patch step and the measurement. "
        f"Timed while {data['workers']} worker process(es) ran the sweep side by side (the "
        "machine is in the table at the end of the page): the seconds compare the runs of "
        "this sweep with each other; another machine gives other seconds.\n\n"
        + _cheapest_table(data) + "\n\n"
        "![measured Pareto front](wave_simulation_pareto.png)\n\n"
        "### Space and time apart\n\n"
        "Each run's fully discrete error beside its semi-discrete (space only) twin. At a "
        "fixed Courant number the step shrinks with the element, so what central differences "
        "add falls like N^-2 whatever the rule, while the mesh's own error falls like its "
        "order (N^-2p for a rule that keeps the consistent order): the semi-discrete curves "
        "show the order the fully discrete ones hide.\n\n"
        + _split_summary(data) + "\n\n"
        "![space and time apart](wave_simulation_split.png)\n\n"
        "### Does the dispersion analysis predict the simulation?\n\n"
        "Prediction: the fully discrete branch of the Bloch plate patch with the run's "
        "thickness mesh, aspect ratio, rule and step (`dispersion.simulation."
        "dispersion_prediction`), at the burst's centre frequency (the group delay and phase of "
        "the carrier), and over the whole band: the energy centroid of a single mode travels "
        "exactly at its group delay averaged over its energy spectrum, so the branch's group "
        "velocity at every frequency, weighted by the spectrum the run received at the "
        "reference station, predicts the energy arrival. A prediction holds where the measured "
        "error lies within the run's own tolerance, a rule stated before the runs: the floor "
        "(the disagreement of the converged verification run for that measure: "
        f"{_floors(data)}), plus the change of the measured error between half the travel and "
        "all of it (a uniformly travelling mode has the same relative error at both), plus for "
        "the envelope peak the difference of the two arrival estimates, plus for a prediction "
        "at the carrier alone its difference from the band-averaged one. The reasons below are "
        "stated rules applied to each run's own numbers.\n\n"
        + _prediction_summary(data) + "\n\n"
        "![predicted against measured](wave_simulation_prediction.png)\n\n"
        "### Signals\n\n![signals against the exact reference](wave_simulation_signals.png)\n\n"
        "### What the seconds hold\n\n"
        + _costs_summary(data) + "\n\n"
        "The cost-accuracy chart models the cost as steps per unit time x DOFs x the rule's "
        "modelled work per DOF and step (a stiffness row plus a division, a banded product or "
        "a solve); the loop's seconds say what each step costs on this machine. Were the model "
        "right, every marker would lie on one line.\n\n"
        "![measured against modelled cost](wave_simulation_costs.png)\n\n"
        + _modelled_table(data) + "\n\n"
        "### The strip's thickness\n\n"
        "The strip is the scene's plate, 2H thick, meshed through its thickness by the rule "
        "that meshes its length (elements within a wavelength over N): one to three elements "
        "at these N, all the scene needs, for every rule alike. A factorized (consistent) "
        "mass's band grows with the elements through the thickness, so what a thicker mesh "
        "costs each step is measured instead (the explicit loop of the same strip at the base "
        "N with more elements through the thickness, zero load, the median of five timed "
        f"segments): {_thickness_summary(data)}. A structure meshed with more elements across "
        "its thickness pays the lower rows of the table.\n\n"
        + _thickness_table(data) + "\n\n"
        f"Not run:{refused}\n\nFailures of the study:{failures}\n\n"
        "<details><summary>Every run</summary>\n\n" + _points_table(data)
        + "\n\n</details>\n\n"
        "Data: `wave_simulation.json`. Regenerate: `dispersion reproduce --sections "
        "wave_simulation`.\n")
