"""Report section ``ring``: the ring study (Figure 4), its grid, dt sweep, speed, Signorini 1D.

``measure`` is :func:`dispersion.contact.study.measure`; :func:`render` turns the stored
result (``ring.json``) into figures and Markdown without recomputing.
"""
from __future__ import annotations

from pathlib import Path

from dispersion.contact.newmark_scheme import SCHEME_TEXT
from dispersion.contact.roundoff_spread import RING_FLOORS, SIGNORINI_FLOOR
from dispersion.contact.signorini import SIGNORINI_SPREAD_RULE, SPREAD_FIELDS
from dispersion.contact.study import measure
from dispersion.io import save_figure
from dispersion.report.compare import close, timing, unjudged, within

__all__ = ["measure", "render", "summary", "headline", "TOLERANCES"]

_CHAOTIC = ("contact histories are chaotic: a round-off perturbation changes them (the spread "
            "runs measure by how much for the default scene, and those are judged)")


def _spread_rules(mass: str) -> tuple:
    band = {"lo": f"spread.{mass}.energy_min", "hi": f"spread.{mass}.energy_max"}
    events = {"lo": f"spread.{mass}.events_min", "hi": f"spread.{mass}.events_max"}
    e, n = RING_FLOORS["energy_change_percent"], RING_FLOORS["contact_events"]
    return (
        within(f"pair.{mass}.summary.energy_change_percent", **band, widen=1.0, abs=e),
        within(f"spread.{mass}.energy_m*", **band, widen=1.0, abs=e),
        within(f"pair.{mass}.summary.contact_events", **events, widen=1.0, abs=n),
        within(f"spread.{mass}.events_m*", **events, widen=1.0, abs=n),
    )


def _signorini_bands():
    return [(name, {"lo": f"signorini[].spread.{name}.min", "hi": f"signorini[].spread.{name}.max"})
            for name in SPREAD_FIELDS]


#: Comparison rules (:mod:`dispersion.report.compare`), first match wins; inputs, scene,
#: counts and labels not named here must be identical. The ring's energy change and contact
#: events must lie in the reference's spread of round-off-perturbed runs, widened by that
#: spread's width on each side (a few runs sample the spread; one more may fall just outside):
#: at least 1e-6 percentage points and one contact event.
TOLERANCES = (
    timing("seconds.*", "wall time"),
    timing("timing[].ms_per_step", "wall time"),
    timing("*.seconds", "wall time"),
    timing("*[].seconds", "wall time"),
    *(rule for mass in ("lumped", "singular", "consistent") for rule in _spread_rules(mass)),
    unjudged("pair.*.series.*", _CHAOTIC),
    close("pair.*.summary.initial_energy_change_percent", abs=1e-9),
    unjudged("pair.*.summary.*", _CHAOTIC),
    close("grid[].initial_energy_change_percent", abs=1e-9),
    close("dt_sweep[].initial_energy_change_percent", abs=1e-9),
    unjudged("grid[].*", _CHAOTIC),
    unjudged("dt_sweep[].*", _CHAOTIC),
    unjudged("dt_fit.*", "fitted to the chaotic dt sweep"),
    # each error of a 1D Signorini row and its new spread lie in the reference row's spread
    # over the round-off perturbations (SIGNORINI_SPREAD_RULE), widened by its width, at
    # least 1e-6 (rows whose runs all agree: compared to 1e-6)
    *(within(f"signorini[].{name}", **band, widen=1.0, abs=SIGNORINI_FLOOR)
      for name, band in _signorini_bands()),
    *(within(f"signorini[].spread.{name}.m*", **band, widen=1.0, abs=SIGNORINI_FLOOR)
      for name, band in _signorini_bands()),
    unjudged("signorini[].energy_flag", "a sentence quoting the energy growth, which is "
             "judged as a spread (energy_growth_percent)"),
    close("signorini[].min_gap", abs=1e-12, why="penetration at round-off level"),
    close("signorini[].*", rel=1e-6, abs=1e-9,
          why="1D bar with a closed-form solution: not chaotic"),
)

COMMAND = "dispersion reproduce --sections ring"


def _f(x, spec=".3g"):
    return "n/a" if x is None else format(x, spec)


#: Largest rms residual (natural log) of a log-log fit that is still called a power law.
RATE_RESIDUAL_MAX = 0.25


def _err(r: dict, name: str, spec: str = ".3f") -> str:
    """An error of a Signorini row: its range over the row's runs where they differ."""
    s = (r.get("spread") or {}).get(name)
    if s and s["min"] is not None:
        lo, hi = format(s["min"], spec), format(s["max"], spec)
        if lo != hi:
            return f"{lo} .. {hi}"
    return _f(r[name], spec)


def _runs_text(rows: list, count_rule: str = "") -> str:
    runs = sorted({r["spread"]["runs"] for r in rows if r.get("spread")})
    if not runs:
        return ""
    return (" " + SIGNORINI_SPREAD_RULE + (" " + count_rule if count_rule else "")
            + " Runs per row: " + ", ".join(str(n) for n in runs) + ".")


def _rate_text(fit: dict) -> str:
    """What a dt sweep supports: a rate only for >= 4 monotone points that fit a power law."""
    if fit["rate"] is None or fit["points"] < 4 or not fit["monotone"]:
        return (f"no dt rate claimed ({fit['points']} points, monotone: {fit['monotone']})")
    if fit["residual"] > RATE_RESIDUAL_MAX:
        return (f"|energy change| falls monotonically over {fit['points']} step sizes, but "
                f"not as a power law (log-log slope {fit['rate']:.2f}, rms residual "
                f"{fit['residual']:.2f}): no rate claimed")
    return (f"|energy change| falls like dt^{fit['rate']:.2f} over {fit['points']} monotone "
            f"points (rms residual of the log-log fit {fit['residual']:.2f})")


def _rule_check(data: dict) -> str:
    """The rule applied to the measured grid (steps per impact >= 20 at theta0 = 180 deg)."""
    sizes = sorted({r["r_outer"] for r in data["grid"] if r["steps_per_impact"] >= 20
                    and r["theta0_deg"] == 180})
    if not sizes:
        return "The grid of this run holds no size with 20 steps per impact (quick mode)."
    return (f"Applied to the grid below, the rule picks r_outer = {sizes[0]:g} m "
            f"(the default scene has r_outer = {data['default_r_outer']:g} m).")


def _run_cell(r: dict) -> str:
    if r.get("status") != "ok":
        return r.get("status", "n/a")
    return f"{r['energy_change_percent']:+.3g} % ({r['contact_events']})"


def _robust_text(data: dict) -> list[str]:
    """The dt and round-off spread of the shown scene and the part of each figure that is
    robust: the smallest loss over every run (all runs listed)."""
    ds = data.get("dt_spread")
    if not ds:
        return []
    lines = ["", "Over both round-off and dt (every run of the scene at dt = "
             + ", ".join(f"{r['dt']:g}" for r in ds["lumped"]["runs"])
             + f" s, and the {data['spread']['lumped']['runs']} / "
               f"{data['spread']['singular']['runs']} round-off runs):", "",
             "| mass | dt (s): energy change % (contact events) | runs | range over all runs "
             "(%) | contact events | robust part |", "|---|---|---|---|---|---|"]
    for m in ("lumped", "singular"):
        d = ds[m]
        per_dt = ", ".join(f"{r['dt']:g}: " + (f"{r['energy_change_percent']:+.3g} "
                                                f"({r['contact_events']})" if r["converged"]
                                                else "Newton failed") for r in d["runs"])
        worst_case_loss = -d["energy_max"]  # the smallest loss of every run
        robust = (f"a loss of at least {worst_case_loss:.3g} % in every run"
                  if worst_case_loss > 0 else "no loss common to every run")
        lines.append(f"| {m} | {per_dt} | {d['all_runs']} | {d['energy_min']:+.4g} .. "
                     f"{d['energy_max']:+.4g} | {d['events_min']}-{d['events_max']} | {robust} |")
    lum, sing = ds["lumped"], ds["singular"]
    lines += ["", (f"What is robust: the lumped mass loses between {-lum['energy_max']:.3g} % and "
                   f"{-lum['energy_min']:.3g} % over these runs, with "
                   f"{lum['events_min']}-{lum['events_max']} contact events; the part above "
                   f"{-lum['energy_max']:.3g} % moves with dt and round-off (its chatter), so "
                   "no single lumped figure is quoted without this range. The singular mass "
                   f"stays within {sing['energy_min']:+.3g} .. {sing['energy_max']:+.3g} % "
                   f"({sing['events_min']}-{sing['events_max']} events).")]
    return lines


def _flag_cell(r: dict) -> str:
    if "energy_flag" not in r:
        return "not judged (older record)"
    return "UNSTABLE: " + r["energy_flag"] if r["energy_flag"] else "ok"


def _scheme_text(data: dict) -> str:
    """The integrator of the shown scene, from the pair's stored summaries."""
    names = dict.fromkeys(data["pair"][m]["summary"].get("scheme") for m in ("lumped", "singular"))
    return " / ".join(SCHEME_TEXT.get(n, str(n)) for n in names if n) or "scheme not recorded"


def _elements_text(rows: list) -> str:
    """The element counts of the Signorini rows, as stored (older records did not store it)."""
    counts = sorted({r["n_elements"] for r in rows if "n_elements" in r})
    if not counts:
        return "element count not recorded (older record)"
    return " / ".join(str(c) for c in counts) + " elements"


def _pair_lines(data: dict) -> list[str]:
    """The README's lines on the shown scene: its size and step, and each mass's energy
    change with the spread of its round-off runs."""
    pair, spread, sc = data["pair"], data["spread"], data["scenario"]
    lines = [f"Ring scene r = {sc['r_inner']:g}-{sc['r_outer']:g} m, dt = {sc['dt']:g} s "
             f"({data['steps_per_impact']:.0f} steps per impact), {_scheme_text(data)}:"]
    for m in ("lumped", "singular"):
        s, sp = pair[m]["summary"], spread[m]
        if not s.get("converged"):
            lines.append(f"- {m} mass: Newton failed.")
            continue
        lines.append(f"- {m} mass: energy change {s['energy_change_percent']:+.4g} % "
                     f"({sp['runs']} runs with round-off perturbations: "
                     f"{sp['energy_min']:+.4g} .. {sp['energy_max']:+.4g} %), "
                     f"{sp['events_min']}-{sp['events_max']} contact events "
                     f"(paper: {data['paper'][m]:+g} %).")
    return lines


def _sweep_line(data: dict) -> str:
    return (f"- singular mass, the default scene scaled by {data['sweep_scale']:g}: "
            f"{_rate_text(data['dt_fit'])}.")


def render(data: dict, out: Path) -> str:
    """Write ``figure4.png`` and ``ring_grid.png`` into ``out``; return the Markdown."""
    from dispersion.plotting.ring import figure4, plot_grid

    out = Path(out)
    sc = data["scenario"]
    pair = data["pair"]
    lines = [
        "## Ring benchmark: lumped vs singular mass (paper sec. 3, Figure 4)",
        "",
        ("**How the scene was chosen.** " + data["rule"]),
        "",
        _rule_check(data),
        "",
        "Every earlier default scene of `dispersion/contact/scenario.py` (its git history), "
        f"run again by this study with {_scheme_text(data)}: energy change in % (contact "
        "events).",
        "",
        "| scene | note | steps per impact | lumped | singular |",
        "|---|---|---|---|---|",
    ]
    for h in data["scene_history"]:
        if not isinstance(h, dict):  # a record from before the measured history
            scene, note, lum, sing = h
            lines.append(f"| {scene} | {note} (figures typed then, not measured) | - | "
                         f"{_f(lum, '+.3g')} % | {_f(sing, '+.3g')} % |")
            continue
        cells = [_run_cell(h[m]) for m in ("lumped", "singular")]
        lines.append(f"| {h['scene']} | {h['note']} | {h['steps_per_impact']:.1f} | "
                     f"{cells[0]} | {cells[1]} |")
    lines += [
        "",
        (f"Scene shown{' (quick mode: the default scene scaled by 1/8)' if data['quick'] else ''}"
         f": quarter ring r = {sc['r_inner']:g}-{sc['r_outer']:g} m, arc from "
         f"{sc['theta0_deg']:g} deg, gap {sc['gap']:g} m, E = {sc['E']:.4g} Pa (derived from "
         f"v0/c_T = {sc['v0_over_cT']:g}), nu = {sc['nu']:g}, rho = {sc['rho']:g} kg/m^3, "
         f"v0 = {sc['v0']:g} m/s, {sc['n_xi_elements']} x {sc['n_eta_elements']} quadratic "
         f"NURBS elements, dt = {sc['dt']:g} s, t_end = {sc['t_end']:g} s, "
         f"{data['steps_per_impact']:.1f} steps per impact; {_scheme_text(data)}."),
        "",
    ]
    if pair["lumped"]["series"] and pair["singular"]["series"]:
        fig = figure4(pair["lumped"], pair["singular"], data["paper"], data["scenario"])
        save_figure(fig, out / "figure4.png", dpi=110)
        lines += ["![Figure 4](figure4.png)", ""]
    lines += [
        "| mass | energy change (%) | runs | spread of energy change (%) | contact events "
        "| max penetration at Greville points (m) | between them (m) | rotation (deg) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for m in ("lumped", "singular"):
        s, sp = pair[m]["summary"], data["spread"][m]
        if not s.get("converged"):
            lines.append(f"| {m} | Newton failed | | | | | | |")
            continue
        lines.append(
            f"| {m} | {s['energy_change_percent']:+.4g} | {sp['runs']} | "
            f"{sp['energy_min']:+.4g} .. {sp['energy_max']:+.4g} | "
            f"{sp['events_min']}-{sp['events_max']} | {s['max_penetration_greville']:.1e} | "
            f"{s['max_penetration']:.2g} | {s['final_rotation_deg']:.0f} |")
    lines += [
        "",
        (f"Paper: lumped {data['paper']['lumped']} %, singular {data['paper']['singular']} %. "
         "Spread: the same run repeated with the initial velocity perturbed by "
         f"{data['spread']['lumped']['perturbation']:g} (relative, random per DOF); the lumped "
         "mass chatters (many short contacts), so its figures move between runs. "
         + (data["spread_rule"] + " " if data.get("spread_rule") else "")
         + "Penetration: the constraint holds at the Greville points of the outer surface "
         "(first column, round-off); the boundary between them is sampled at 8 points per "
         "element."),
        *_robust_text(data),
        "",
        "### The energy figures over the grid (size and landing angle)",
        "",
    ]
    fig = plot_grid(data["grid"], data["paper"], default_steps=data["default_steps_per_impact"])
    save_figure(fig, out / "ring_grid.png", dpi=110)
    lines += [
        "![grid](ring_grid.png)",
        "",
        "| r_outer (m) | steps per impact | arc from (deg) | lumped (%) | singular (%) "
        "| lumped events | singular events |",
        "|---|---|---|---|---|---|---|",
    ]
    keys = sorted({(r["r_outer"], r["theta0_deg"]) for r in data["grid"]})
    for r_out, ang in keys:
        by = {r["mass"]: r for r in data["grid"] if r["r_outer"] == r_out
              and r["theta0_deg"] == ang}
        spi = next(iter(by.values()))["steps_per_impact"]
        cells = [_f(by[m].get("energy_change_percent"), "+.3g") if m in by else "n/a"
                 for m in ("lumped", "singular")]
        ev = [str(by[m].get("contact_events", "n/a")) if m in by else "n/a"
              for m in ("lumped", "singular")]
        lines.append(f"| {r_out:g} | {spi:.1f} | {ang:g} | {cells[0]} | {cells[1]} | "
                     f"{ev[0]} | {ev[1]} |")
    fit = data["dt_fit"]
    lines += [
        "",
        "### Singular mass: energy change against the time step",
        "",
        f"The default scene scaled by {data['sweep_scale']:g} (radii, gap, end time), same "
        "end time for every step.",
        "",
        "| dt (s) | energy change (%) |",
        "|---|---|",
    ]
    lines += [f"| {r['dt']:g} | {_f(r.get('energy_change_percent'), '+.3g')} |"
              for r in data["dt_sweep"]]
    lines.append("\n" + _rate_text(fit) + ".")
    lines += [
        "",
        "### Speed: time per step against the number of elements (singular mass)",
        "",
        "Mean wall time of the steps through the first impact, each step timed by the "
        "integrator's progress callback (assembly and set-up excluded).",
        "",
        "| level | elements | DOFs | steps | ms per step |",
        "|---|---|---|---|---|",
    ]
    lines += [f"| {r['level']} | {r['elements']} | {r['dofs']} | {r['steps']} | "
              f"{r['ms_per_step']:.2f} |" for r in data["timing"]]
    lines += [
        "",
        "### GetFEM's 1D Signorini bar (exact solution of period 3, energy 1/8)",
        "",
        ("; ".join(f"p = {p}: dt {dt:g}, schemes " + ", ".join(
            dict.fromkeys(r["scheme"] for r in data["signorini"] if r["p"] == p))
            for p, dt in sorted({(r["p"], r["dt"]) for r in data["signorini"]}))
         + f"; {_elements_text(data['signorini'])}, T = {data['signorini'][0]['t_end']:g}. "
         "Every scheme is shown on its "
         "own row (no best-of). Energy drift: largest change of the total energy after t = 0 "
         "(% of 1/8); initial state: energy the consistent initial state changed (massless "
         "DOF in equilibrium, % of 1/8); errors: relative L2-in-time errors at x = 0 against "
         "the exact solution; s: wall time of the row's runs, stepped together, per run; "
         "energy balance: flagged UNSTABLE when the total energy grows "
         "beyond the stated bound or the scheme is known to be unstable with that mass "
         "(`dispersion.contact.energy_balance`), and such a row is not a result."
         + _runs_text(data["signorini"], data.get("spread_rule", ""))),
        "",
        "| p | mass | scheme | energy drift (%) | initial state (%) | u(0) | v(0) "
        "| contact stress | s | energy balance |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in data["signorini"]:
        lines.append(f"| {r['p']} | {r['mass']} | {r['scheme']} | "
                     f"{_err(r, 'energy_drift_percent', '.2g')} | "
                     f"{r['initial_energy_change_percent']:+.3g} | {_err(r, 'u0_rel_l2')} | "
                     f"{_err(r, 'v0_rel_l2')} | {_err(r, 'stress_rel_l2')} | "
                     f"{r['seconds']:.2f} | {_flag_cell(r)} |")
    lines += ["", ("Side by side with GetFEM on the same discretization: "
                   "`python benchmarks/bench_getfem.py`."),
              "", f"Regenerate: `{COMMAND}`; measured in {data['seconds']['total']:.0f} s.", ""]
    return "\n".join(lines)


#: The degree of the Signorini rows the README block quotes (the selection names its label).
SUMMARY_P = 1


def _legacy_summary(data: dict) -> str:
    """A record from before the per-scheme figures and the dt spread (no ``dt_spread``)
    renders as it was stored; ``dispersion reproduce`` replaces it."""
    sig = [r for r in data["signorini"] if r["p"] == SUMMARY_P]
    best = {m: min(r["stress_rel_l2"] for r in sig if r["mass"] == m)
            for m in ("lumped", "consistent", "singular")}
    return "\n".join([
        *_pair_lines(data),
        _sweep_line(data),
        f"- 1D Signorini bar (P{SUMMARY_P}): relative L2 error of the contact stress lumped "
        f"{best['lumped']:.3f}, consistent {best['consistent']:.3f}, singular "
        f"{best['singular']:.3f}.",
    ]) + "\n"


def headline(data: dict) -> str:
    """One line for the console: the ring's energy change per mass against the paper's.

    >>> headline({"paper": {"lumped": -9.5}, "pair": {"lumped": {"summary": {
    ...     "converged": True, "energy_change_percent": -10.04}}},
    ...     "spread": {"lumped": {"runs": 4, "energy_min": -10.04, "energy_max": -8.94}}})
    'Ring (Figure 4, figure4.png), energy change: lumped -10.04 % (4 round-off runs -10.04 .. -8.94 %; paper -9.5 %).'
    """
    cells = []
    for m, paper in data["paper"].items():
        s, sp = data["pair"][m]["summary"], data.get("spread", {}).get(m)
        if not s.get("converged"):
            cells.append(f"{m} Newton failed (paper {paper:+g} %)")
            continue
        band = ""
        if sp:
            lo, hi = f"{sp['energy_min']:+.4g}", f"{sp['energy_max']:+.4g}"
            band = f"{sp['runs']} round-off runs " + (f"all {lo} %; " if lo == hi
                                                      else f"{lo} .. {hi} %; ")
        cells.append(f"{m} {s['energy_change_percent']:+.4g} % ({band}paper {paper:+g} %)")
    return "Ring (Figure 4, figure4.png), energy change: " + ", ".join(cells) + "."


def summary(data: dict) -> str:
    """The README's ring block: the shown scene's energy figures with their spread."""
    if "dt_spread" not in data:
        return _legacy_summary(data)
    cells = []
    for m in ("lumped", "singular"):
        d = data["dt_spread"][m]
        cells.append(f"- {m} mass over dt = " + ", ".join(f"{r['dt']:g}" for r in d["runs"])
                     + f" s and the round-off runs ({d['all_runs']} runs): "
                     f"{d['energy_min']:+.4g} .. {d['energy_max']:+.4g} %, "
                     f"{d['events_min']}-{d['events_max']} contact events.")
    sig = [r for r in data["signorini"] if r["p"] == SUMMARY_P]
    per_scheme = []
    for scheme in dict.fromkeys(r["scheme"] for r in sig):
        rows = {r["mass"]: r for r in sig if r["scheme"] == scheme}
        text = ", ".join(f"{m} {_err(rows[m], 'stress_rel_l2')}"
                         + (" (UNSTABLE: not a result)" if rows[m].get("energy_flag") else "")
                         for m in ("lumped", "consistent", "singular") if m in rows)
        per_scheme.append(f"  - {scheme}: {text}")
    spread = [r["spread"]["runs"] for r in sig if r.get("spread")]
    over = (f" (range over {max(spread)} runs, the wall moved by 0..{max(spread) - 1} units "
            "of 2^-53)" if spread else "")
    steps = ", ".join(f"dt {dt:g}" for dt in dict.fromkeys(r["dt"] for r in sig))
    return "\n".join([
        *_pair_lines(data),
        *cells,
        _sweep_line(data),
        f"- 1D Signorini bar (P{SUMMARY_P}, {_elements_text(sig)}, {steps}): relative L2 "
        f"error of the contact stress{over}, per scheme:",
        *per_scheme,
    ]) + "\n"
