"""Report section "branches": renders :func:`dispersion.studies.branch_study.measure_branches` from JSON.

``measure`` (imported from :mod:`dispersion.studies.branch_study`) runs the study; :func:`render`
takes the stored result (plain JSON types) and writes ``figure2.png``,
``branches_velocities.png``, ``branches_per_wavelength.png``, ``branches_shapes.png``,
``branches_speed_accuracy.png`` and the Markdown, computing nothing.
"""
from __future__ import annotations

from pathlib import Path

from dispersion.studies.branch_study import measure_branches as measure
from dispersion.io import save_figure
from dispersion.report.compare import close, timing

__all__ = ["measure", "render", "report", "summary", "TOLERANCES"]

#: Comparison rules (:mod:`dispersion.report.compare`), first match wins; every field not
#: named (grids, labels, counts, symmetries) must be identical. Exact roots to 1e-12 (the
#: tracer's accuracy against 40-digit mpmath); discrete roots to 1e-10 (the accuracy the
#: discrete solver states); derivatives, shapes and MAC, which lose digits to conditioning,
#: to 1e-8; relative errors below 1e-13 are round-off, not data (``ROUND_OFF`` of the plots).
TOLERANCES = (
    timing("discrete_speed[].time_s", "wall time"),
    timing("discrete_speed[].points_per_s", "wall time"),
    timing("tracer.rows[].time_s", "wall time"),
    close("exact.*.omega[]", rel=1e-12, abs=1e-12),
    close("exact.*[]", rel=1e-8, abs=1e-9, why="velocities: implicit differentiation"),
    close("discrete.*.omega.*[]", rel=1e-10, abs=1e-12),
    close("discrete.*.paired_error.*[]", abs=1e-10),
    close("discrete.*.group.*[]", rel=1e-8, abs=1e-9),
    close("discrete.*.mac.*[]", abs=1e-8),
    close("discrete.*.zone_edge", rel=1e-14),
    close("mpmath_error", abs=1e-12, why="round-off-level maximum: below 1e-12 either way"),
    close("tracer.reference_mpmath_error", abs=1e-12),
    close("tracer.rows[].error", rel=1e-6, abs=1e-13),
    close("discrete_speed[].error", rel=1e-6, abs=1e-13),
    close("orders[].error[]", rel=1e-6, abs=1e-13),
    close("orders[].fitted", abs=1e-6),
    close("orders[].max_log_residual", abs=1e-6),
    close("per_wavelength.curves[].error[]", rel=1e-6, abs=1e-13),
    close("bar.error.*[]", rel=1e-9, abs=1e-13),
    close("shapes.modes[].exact[][]", abs=1e-8),
    close("shapes.modes[].discrete[][]", abs=1e-8),
    close("shapes.modes[].mac", abs=1e-8),
    close("shapes.modes[].omega", rel=1e-12),
    close("shapes.modes[].omega_h", rel=1e-10),
    close("zgv[].*", rel=1e-9),
    close("fd_per_omega_aluminium", rel=1e-14),
)


def _fmt(x, spec=".3g") -> str:
    return "-" if x is None else format(x, spec)


def _patch_heading(f: dict) -> str:
    """The geometry a fit was computed on, rendered from the fields the result carries
    (:meth:`dispersion.symbolic.patch.Patch.as_dict`)."""
    geom = f"Bloch r = b/h = {f['r']}" if f["model"] == "bloch" else "x-exact"
    return f"{geom}, p = {f['p']}, n = {f['n']}"


def _mass_cell(f: dict) -> str:
    """The mass variant, with its contact set and weight where they apply (singular)."""
    if not f["mass"].startswith("singular"):
        return f["mass"]
    if f.get("weights"):
        return f"{f['mass']} (weights {f['weights']})"
    return f"{f['mass']} (contact {f['contact']}, gamma_s = {f['gamma_s']})"


def _window(o: dict) -> str:
    w = o.get("window")
    return "empty" if not w else f"[{w[0]:.3g}, {w[1]:.3g}]"


def _order_cell(o: dict) -> str:
    return f"{o['fitted']:.2f}" if o.get("verdict") == "fitted" else f"none: {o['verdict']}"


def _series_cell(o: dict) -> str:
    if o.get("series_order") is None:
        return "no error term"
    return f"{o['series_leading_coefficient']:+.3g} kappa^{o['series_order']}"


def _order_tables(orders) -> list[str]:
    """One table per patch: window, points, fitted order, residual and the series' prediction."""
    from dispersion.studies.asymptotic_fit import (ERROR_FLOOR, LEAD_OVER_REST, POINTS,
                                                   RESIDUAL_MAX)

    lines = [
        "Order of the relative error |Omega_h / Omega - 1| (shape-paired), fitted by least "
        f"squares on log-log over {POINTS} geometric kappas inside the window where the "
        "series of the error (discrete minus exact series, "
        "`dispersion.studies.asymptotic_fit`) has its leading term at least "
        f"{LEAD_OVER_REST:g}x the sum of the later known terms and at least {ERROR_FLOOR:g} "
        f"(1000x the solvers' accuracy); no order if the window is empty or the largest log "
        f"residual exceeds {RESIDUAL_MAX:g}. 'Series slope' is the least-squares slope of the "
        "truncated series itself on the same points.", ""]
    headings = list(dict.fromkeys(_patch_heading(o["patch"]) for o in orders))
    for head in headings:
        lines += [f"**{head}**", "",
                  "| mass | branch | series of the error | window (kappa) | points | fitted order "
                  "| max log residual | series slope |", "|---|---|---|---|---|---|---|---|"]
        for o in (o for o in orders if _patch_heading(o["patch"]) == head):
            lines.append(f"| {_mass_cell(o['patch'])} | {o['branch']} | {_series_cell(o)} | "
                         f"{_window(o)} | "
                         f"{o['points']} | {_order_cell(o)} | "
                         f"{_fmt(o['max_log_residual'], '.2g')} | "
                         f"{_fmt(o['series_slope'], '.3f')} |")
        lines.append("")
    return lines


def _legacy_order_table(orders) -> list[str]:
    """A record from before the windowed fits (no ``patch`` per row) renders as it was stored;
    ``dispersion reproduce`` replaces it."""
    lines = ["| mass | branch | fitted order of the relative error | points | max log residual "
             "| monotone | series predicts |", "|---|---|---|---|---|---|---|"]
    for o in orders:
        lines.append(f"| {o['mass']} | {o['branch']} | {_fmt(o['fitted'], '.2f')} | {o['points']} "
                     f"| {_fmt(o['max_log_residual'], '.2g')} | {'yes' if o['monotone'] else 'no'} "
                     f"| {o['series']} |")
    return lines


def _orders_block(orders) -> list[str]:
    if any("patch" not in o for o in orders):
        return _legacy_order_table(orders)
    return _order_tables(orders)


def render(data: dict, out: Path) -> str:
    """Figures and Markdown of the branches study from its stored JSON ``data``."""
    from dispersion.plotting import branches as plots

    out = Path(out)
    r = data["r_figure2"]
    fig2 = {"nu": data["nu"], "kappa": data["kappa"], "omega_max": data["omega_max"],
            "exact": data["exact"], "discrete": data["discrete"]}
    save_figure(plots.figure2(fig2, title=_figure2_title(data, r)), out / "figure2.png", dpi=130)
    save_figure(plots.figure_velocities(fig2, fd_per_omega=data["fd_per_omega_aluminium"],
                                        zgv=data["zgv"]),
                out / "branches_velocities.png", dpi=130)
    save_figure(plots.figure_per_wavelength(data["per_wavelength"], data["bar"], nu=data["nu"]),
                out / "branches_per_wavelength.png", dpi=130)
    save_figure(plots.figure_shapes(data["shapes"]), out / "branches_shapes.png", dpi=130)
    save_figure(plots.figure_speed_accuracy(data["tracer"], data["discrete_speed"]),
                out / "branches_speed_accuracy.png", dpi=130)

    lines = ["## Dispersion branches (Figure 2, right)", ""]
    if data["quick"]:
        lines += ["*Quick subset: coarser kappa grids, fewer solver settings.*", ""]
    lines += [
        "![Figure 2](figure2.png)", "",
        f"Exact Rayleigh-Lamb branches (nu = {data['nu']}) and {_figure2_patches(data, r)}, "
        f"{len(data['kappa'])} kappa points. Right: the signed relative error of each exact "
        "branch against the discrete mode of the same through-thickness shape (modal assurance "
        "criterion >= 0.5), not against the discrete mode of the same index."
        + _symmetry_note(data), "",
        f"Traced roots against 40-digit mpmath ({data['mpmath_points']} random roots): max "
        f"relative error {data['mpmath_error']:.1e}; tracer failures reported: "
        f"{len(data['exact_failures'])}.", "",
    ]
    lines += _orders_block(data["orders"])
    zgv = ", ".join(f"{z['label']} at kappa = {z['kappa']:.6f}, Omega = {z['omega']:.6f}"
                    for z in data["zgv"]) or "none"
    lines += [
        "", "### Velocities", "",
        "![velocities](branches_velocities.png)", "",
        "Phase velocity Omega/kappa and group velocity dOmega/dkappa (in units of c_T) of the "
        "exact branches (implicit differentiation of the frequency function) and of the "
        "consistent-mass patch (eigenvector formula). Top axis: frequency-thickness for "
        "aluminium. Zero-group-velocity points of the exact branches with kappa <= 8: "
        f"{zgv}.", "",
        "### Discretization error per wavelength", "",
        "![per wavelength](branches_per_wavelength.png)", "",
        "Magnitude of the relative phase-velocity error (equal to the frequency error at the "
        "same wavenumber) against elements per wavelength, on log-log axes, for the plate's S0 "
        "and A0 and for the 1D bar; its sign by line style (solid: the discrete wave is too "
        "fast, dashed: too slow), so a sign change is a gap in the curve. Colour: mass; "
        "marker: degree p. Values below 1e-13 are round-off and are not drawn.", "",
        "### Mode shapes", "",
        "![mode shapes](branches_shapes.png)", "",
        "### Speed and accuracy", "",
        "![speed and accuracy](branches_speed_accuracy.png)", "",
    ]
    fast = [row for row in data["tracer"]["rows"] if row["rtol"] <= 1e-12]
    if fast:
        best = min(fast, key=lambda row: row["time_s"])
        lines.append(f"Tracer at rtol <= 1e-12: {best['time_s']:.3f} s for "
                     f"{data['tracer']['kappa_count']} kappa points (all branches with Omega "
                     f"<= {data['tracer']['omega_max']:g}), max relative error "
                     f"{_fmt(best['error'], '.1e')} against the reference setting, whose own "
                     f"error against 40-digit mpmath is "
                     f"{data['tracer']['reference_mpmath_error']:.1e}.")
    lines += ["", "Data: [branches.json](branches.json).", ""]
    return "\n".join(lines)


def report(out: Path, quick: bool = False, executor=None) -> str:
    """Measure, store ``branches.json`` and render (the one-call form ``reproduce`` runs)."""
    from dispersion.results import load, save

    out = Path(out)
    save(out / "branches.json", "branches", measure(quick=quick, executor=executor),
         inputs={"quick": quick})
    return render(load(out / "branches.json")["result"], out)


def summary(data: dict) -> str:
    """The README block: tracer accuracy, zero-group-velocity points and fitted error orders."""
    fails = len(data.get("exact_failures") or [])
    lines = [
        f"- Exact branches at nu = {data['nu']:g}: {data['mpmath_points']} traced roots against "
        f"40-digit mpmath roots, largest relative error {_fmt(data['mpmath_error'])}; "
        f"{fails} kappa listed as failures.",
        "- Zero-group-velocity points: " + ", ".join(
            f"{z['label']} at kappa = {z['kappa']:.6f}, Omega = {z['omega']:.6f}"
            for z in data["zgv"]) + ".",
        "",
    ]
    lines += _orders_block(data["orders"])
    return "\n".join(lines).rstrip("\n") + "\n"


def _figure2_specs(data) -> list:
    """The patches of Figure 2 as the study stored them ([] in records from before)."""
    from dispersion.symbolic.patch import Patch

    stored = [d.get("patch") for d in data["discrete"].values()]
    return [Patch.from_dict(p) for p in stored] if stored and all(stored) else []


def _figure2_patches(data, r) -> str:
    """The discrete side of Figure 2's caption: geometry once, then each mass, as stored."""
    from dispersion import defaults

    specs = _figure2_specs(data)
    if not specs:
        return f"the discrete branches of the Bloch model with r = b/h = {r:g}"
    paper = (" (the aspect ratio of the paper's Figure 2)"
             if specs[0].r == defaults.FIGURE2_R else "")
    return (f"the discrete branches of the patch {specs[0].geometry_title()}{paper} with "
            + ", ".join(sp.mass_title() for sp in specs))


def _symmetry_note(data) -> str:
    """Why some singular modes get no error curve, for the contact set the run used."""
    sides = dict.fromkeys(sp.contact for sp in _figure2_specs(data)
                          if sp.singular and sp.weights is None and sp.contact != "both")
    if not sides:
        return ""
    return (f" With contact on the {' / '.join(sides)} surface the singular mass breaks the "
            "mirror symmetry; its higher modes resemble no exact branch (MAC < 0.5) and get "
            "no error curve.")


def _figure2_title(data, r) -> str:
    """The title of Figure 2 from the patches the study stored (geometry once, each mass with
    its contact set and gamma_s); older records without patches keep their stored r."""
    specs = _figure2_specs(data)
    if specs:
        return (f"nu = {data['nu']}, {specs[0].geometry_title()}; "
                + ", ".join(sp.mass_title() for sp in specs))
    return f"nu = {data['nu']}, Bloch model, r = b/h = {r:g}"
