"""Report section "studies": renders :func:`dispersion.studies.paper_studies.measure_studies` from JSON.

``measure`` (imported from :mod:`dispersion.studies.paper_studies`) runs the studies; :func:`render` takes the
stored result (plain JSON types) and writes ``studies_gamma.png``, ``studies_radius.png`` and
the Markdown, computing nothing.
"""
from __future__ import annotations

from pathlib import Path

from dispersion.io import save_figure
from dispersion.report.compare import close
from dispersion.studies.paper_studies import measure_studies as measure

__all__ = ["measure", "render", "report", "TOLERANCES"]

#: Comparison rules (:mod:`dispersion.report.compare`), first match wins; grids, orders,
#: labels and counts not named here must be identical. Series coefficients are exact
#: rationals evaluated in floating point (1e-12); errors against the exact series lose digits
#: to cancellation (1e-8 relative, round-off below 1e-13); time steps from eigenvalues (1e-10);
#: the bar impact runs are contact histories, judged to 1e-6.
TOLERANCES = (
    close("gamma[].*_error[]", rel=1e-8, abs=1e-13),
    close("gamma[].*.*", rel=1e-12, abs=1e-15),
    close("orders[].*.*", rel=1e-12, abs=1e-15),
    close("dt_crit[].dt_crit", rel=1e-10),
    close("radius[].deviation[]", rel=1e-8, abs=1e-12),
    close("radius[].kappa_star", rel=1e-8),
    close("bar[].*", rel=1e-6, abs=1e-9),
)


def render(data: dict, out: Path) -> str:
    """Figures and Markdown of the studies from their stored JSON ``data``."""
    from dispersion.plotting import studies as plots

    out = Path(out)
    save_figure(plots.figure_gamma(data["gamma"], data["kappas"], exact=data.get("exact"),
                                   nu=data["nu"], r=data["r"]),
                out / "studies_gamma.png", dpi=120)
    save_figure(plots.figure_radius(data), out / "studies_radius.png", dpi=120)
    return _markdown(data)


def report(out: Path, quick: bool = False, executor=None) -> str:
    """Measure, store ``studies.json`` and render (the one-call form ``reproduce`` runs)."""
    from dispersion.results import load, save

    out = Path(out)
    save(out / "studies.json", "studies", measure(quick=quick, executor=executor),
         inputs={"quick": quick})
    return render(load(out / "studies.json")["result"], out)


def _fmt(x, digits: int = 4) -> str:
    return "-" if x is None else f"{x:.{digits}g}"


def _bar_text(rows: list) -> str:
    """The bar of study (c) as its rows stored it (degree and Courant number)."""
    kinds = dict.fromkeys((r["p"], r["courant"]) for r in rows if "p" in r and "courant" in r)
    if not kinds:
        return "a B-spline bar (degree and step not recorded in this older result)"
    return " / ".join(f"a B-spline bar of degree {p} at Courant number {c:g}" for p, c in kinds)


def _contact_text(d: dict) -> str:
    """The contact set of the singular masses, as the studies' patches stored it."""
    from dispersion.symbolic.patch import Patch

    rows = [row for key in ("gamma", "orders", "dt_crit", "radius") for row in d.get(key, ())]
    specs = [Patch.from_dict(row["patch"]) for row in rows if row.get("patch")]
    sides = dict.fromkeys(sp.contact for sp in specs if sp.singular)
    return f", contact on the {' / '.join(sides)} surface" if sides else ""


def _mass_cell(row: dict) -> str:
    """The row's mass as its stored patch states it (contact and gamma_s for a singular one)."""
    if not row.get("patch"):
        return row["mass"]  # an older record: the mass name only
    from dispersion.symbolic.patch import Patch

    return Patch.from_dict(row["patch"]).mass_title().replace(" mass", "", 1)


def _markdown(d: dict) -> str:
    from dispersion.plotting.studies import gamma_patch_text

    quick = d["quick"]
    nu, r = d["nu"], d["r"]
    lines = ["## Studies beyond the paper", ""]
    lines += [
        f"Bloch patch with square elements (r = b/h = {r}), nu = {nu}{_contact_text(d)}; all "
        "data in [studies.json](studies.json).", "",
        "### (a) The redistribution weight gamma_s", "",
        "The paper uses one weight and leaves others open. Patch: "
        + (gamma_patch_text(d["gamma"]) or "singular mass (not recorded in this older result)")
        + ": the coefficients of Omega^2 and the relative error of Omega against the exact "
        "Rayleigh-Lamb branch, at each gamma_s.", "",
        "![gamma_s study](studies_gamma.png)", "",
    ]
    ks = d["kappas"]
    head = "| gamma_s | S0 k^4 | S0 k^6 | A0 k^6 | " + " | ".join(
        f"S0 err k={k} | A0 err k={k}" for k in ks) + " |"
    lines += [head.replace(" err ", " signed err "), "|" + "---|" * (4 + 2 * len(ks))]
    for row in d["gamma"]:
        errs = " | ".join(f"{_fmt(row['S0_error'][i], 3)} | {_fmt(row['A0_error'][i], 3)}"
                          for i in range(len(ks)))
        lines.append(f"| {row['gamma_s']:.2f} | {_fmt(row['S0'].get('4'))} | "
                     f"{_fmt(row['S0'].get('6'))} | {_fmt(row['A0'].get('6'))} | {errs} |")
    lines += ["", "Errors are signed, (Omega_h - Omega) / Omega: a weight where |error| is "
              "smallest on the grid may only be where the error changes sign, not a weight "
              "that disperses less over the whole branch."]
    k_last = len(ks) - 1
    for branch in ("S0", "A0"):
        rows = d["gamma"]
        errs = [row[f"{branch}_error"][k_last] for row in rows]
        flips = [(rows[j]["gamma_s"], rows[j + 1]["gamma_s"]) for j in range(len(rows) - 1)
                 if errs[j] is not None and errs[j + 1] is not None and errs[j] * errs[j + 1] < 0]
        where = ("changes sign between gamma_s = " + ", ".join(f"{a:.2f} and {b:.2f}"
                                                            for a, b in flips)) if flips \
            else "keeps one sign over the weights run"
        lines.append("")
        lines.append(f"{branch} at kappa = {ks[k_last]}: the signed error {where}.")
    lines += ["", "### (b) Cubic splines and more control points through the thickness", "",
              "Order = lowest power of kappa at which the discrete Omega^2 series differs from "
              "the exact Rayleigh-Lamb series (eqs 14-15); '> N' means they agree up to the "
              "highest power computed, N.", "",
              "| p | n | mass | S0 order | A0 order | S0 k^4 | A0 k^6 |",
              "|---|---|---|---|---|---|---|"]
    for row in d["orders"]:
        s0, a0 = (f"> {row['order']}" if row[f"{b}_order"] is None else row[f"{b}_order"]
                  for b in ("S0", "A0"))
        lines.append(f"| {row['p']} | {row['n']} | {_mass_cell(row)} | {s0} | {a0} | "
                     f"{_fmt(row['S0'].get('4'))} | "
                     f"{_fmt(row['A0'].get('6'))} |")
    lines += ["", "### (c) Where the methods fail", "",
              "Largest stable step of explicit central differences, dt_crit = 2 / max Omega "
              "over the Brillouin zone, in units h/c_T (massless DOFs condensed):", "",
              "| p | n | mass | dt_crit |", "|---|---|---|---|"]
    for row in d["dt_crit"]:
        lines.append(f"| {row['p']} | {row['n']} | {_mass_cell(row)} | {row['dt_crit']:.4f} |")
    lines += ["", f"Radius of validity of the truncated series: the smallest kappa at which "
              f"Omega from the series departs from the numeric branch (exact Rayleigh-Lamb "
              f"root, or the discrete patch's own eigenvalue) by more than "
              f"{d['tol']:g} relative ('-': not within kappa <= pi/r).", "",
              "![radius of the series](studies_radius.png)", "",
              "Deviations below 1e-13 are round-off of the comparison and are not drawn.", "",
              "| branch | series of | truncated after | kappa* |", "|---|---|---|---|"]
    for row in d["radius"]:
        lines.append(f"| {row['branch']} | {row['mass']} | k^{row['order']} | "
                     f"{_fmt(row['kappa_star'], 3)} |")
    lines += ["", "Newmark (beta = 1/4, gamma = 1/2) with and without the contact "
              "modification of Kane et al. (paper eqs 6-10; 'standard': plain Newmark with "
              f"the contact force treated like any other force): {_bar_text(d['bar'])} hitting a "
              "rigid wall (dispersion.contact.bar), whose exact solution conserves "
              "energy and keeps a constant contact stress. Oscillation = standard deviation of "
              "the contact force over the middle of the contact, over rho c v0.", "",
              "| scheme | mass | elements | energy change % | force oscillation | "
              "contact duration error |", "|---|---|---|---|---|---|"]
    for row in d["bar"]:
        lines.append(f"| {row['scheme']} | {row['mass']} | {row['n_elements']} | "
                     f"{row['energy_change_percent']:.3g} | {row['force_oscillation']:.3g} | "
                     f"{row['duration_error']:.3g} |")
    lines.append("")
    if quick:
        lines.insert(2, "*Quick subset: fewer weights, orders and grid points.*\n")
    return "\n".join(lines)
