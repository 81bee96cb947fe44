"""Report section: every mass rule judged on cost and accuracy at once (issue 21).

``measure`` is :func:`dispersion.studies.cost_accuracy.measure`; ``render`` writes
``cost_accuracy.png`` and a table from the stored JSON, computing nothing.
"""
from __future__ import annotations

from pathlib import Path

from dispersion.io import save_figure
from dispersion.report.compare import close
from dispersion.studies.cost_accuracy import measure

__all__ = ["measure", "render", "TOLERANCES"]

#: Comparison rules (:mod:`dispersion.report.compare`). An error is a relative difference of
#: two frequencies, each a root found to round-off (the discrete one certified to 1e-10
#: relative, in practice to ~1e-15): judged to 1e-12 absolute, which round-off of the root
#: solvers meets and a changed discretization does not. The critical step is a maximum over
#: the zone refined to round-off: 1e-10 relative. Counts, names and the Pareto flags: exact.
TOLERANCES = (
    close("points[].*error_*", abs=1e-12, why="relative differences of roots found to round-off"),
    close("points[].tau_crit", rel=1e-10, why="a maximum over the zone, refined to round-off"),
    close("points[].cost", rel=1e-10, why="computed from the critical step"),
)


def _pct(x) -> str:
    return "-" if x is None else f"{100 * x:+.3g} %"


def _advice(points: list[dict]) -> str:
    """Which rule to use at which accuracy: the Pareto points, cheapest first, each the
    cheapest choice for every error target down to its own error."""
    front = sorted((pt for pt in points if pt["pareto"]), key=lambda q: q["cost"])
    lines = ["Which rule at which accuracy (from the Pareto front: the cheapest point whose "
             "error meets the target):", ""]
    upper = None
    for pt in front:
        err = max(abs(pt["error_S0"]), abs(pt["error_A0"]))
        span = (f"error targets from {100 * err:.3g} %" + (f" up to {100 * upper:.3g} %"
                                                            if upper is not None else " up"))
        lines.append(f"- {span}: p = {pt['p']} {pt['mass']} (cost {pt['cost']:.4g})")
        upper = err
    return "\n".join(lines)


def render(data: dict, out: Path) -> str:
    """Chart and Markdown from the stored result of :func:`measure`."""
    from dispersion.plotting.cost_accuracy import plot_cost_accuracy

    out = Path(out)
    fig = plot_cost_accuracy(data)
    save_figure(fig, out / "cost_accuracy.png", dpi=130)
    rows = ["| p | mass | n | r | critical step [H/c_T] | work per DOF (modelled) | cost | "
            "S0 error | A0 error | S0 semi-discrete | A0 semi-discrete | Pareto |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for pt in data["points"]:
        rows.append(f"| {pt['p']} | {pt['mass']} | {pt['n']} | {pt['r']:g} | "
                    f"{pt['tau_crit']:.4g} | {pt.get('work', 1)} | {pt['cost']:.4g} | "
                    f"{_pct(pt['error_S0'])} | "
                    f"{_pct(pt['error_A0'])} | {_pct(pt['semi_error_S0'])} | "
                    f"{_pct(pt['semi_error_A0'])} | {'yes' if pt['pareto'] else ''} |")
    kinds = sorted({(pt["mass"], pt.get("step_kind", "")) for pt in data["points"]})
    steps = "; ".join(f"{m}: {k}" for m, k in kinds if k)
    advice = _advice(data["points"])
    front = ", ".join(f"p = {pt['p']} {pt['mass']}" for pt in
                      sorted(data["points"], key=lambda q: q["cost"]) if pt["pareto"])
    singular = f"contact set {data['contact']}, gamma_s = {data['gamma_s']:g}"
    return (
        "## Cost against accuracy of the mass rules\n\n"
        "![cost against accuracy](cost_accuracy.png)\n\n"
        f"Bloch plate patch, plane strain, nu = {data['nu']:g}, square elements "
        f"(n = max(p + 1, 3) control points through the thickness, r = b/H = 2/(n - p)); "
        f"singular rules: {singular}. Accuracy: signed phase-velocity error of S0 and A0 "
        f"against the exact Rayleigh-Lamb roots at {data['elements_per_wavelength']} elements "
        f"per wavelength, fully discrete with central differences at {data['courant']:g} "
        "times the rule's own critical step (semi-discrete error beside it). That step is the "
        "periodic lattice's (an unbounded or periodic plate): a finite mesh with open ends has "
        "boundary outliers and a smaller step of its own (section finite_patches; `dispersion "
        "timestep --elements N`), which lowers the steps gained by lumping. Cost: time steps "
        "per unit time times degrees of freedom per unit area (all 2n DOFs of a cell, the "
        "massless ones of the singular rules included) times the modelled work of one "
        "explicit step per DOF (stiffness row plus inverse mass, 2D; a dense stiffness "
        "counted on a model problem of 100 x 100 elements): a model, not a measurement (the "
        "measured price of each step is in the wave-simulation section). "
        f"Explicit steps: {steps}. Pareto front (cheapest first): "
        f"{front}.\n\n{advice}\n\n" + "\n".join(rows) + "\n\n"
        "Data: `cost_accuracy.json`. Regenerate: `dispersion reproduce --sections "
        "cost_accuracy`.\n")
