"""Report section: the finite mesh beside the lattice (issue 35).

``measure`` is :func:`dispersion.studies.finite_patches.measure`; ``render`` writes the
figures and tables from the stored JSON alone.
"""
from __future__ import annotations

from pathlib import Path

from dispersion.io import save_figure
from dispersion.report.compare import close, timing, unjudged
from dispersion.studies.finite_patches import measure

__all__ = ["measure", "render", "headline", "TOLERANCES", "FIGURES"]

#: Comparison rules (:mod:`dispersion.report.compare`), first match wins. Frequencies are
#: eigenvalues of float matrices (LAPACK, ARPACK and the bisection of the proof), the same to
#: round-off on any machine: 1e-8 relative (the bracket of a proven bound is 1e-9); the
#: boundary limits are mpmath roots refined from those: 1e-8. Counts, names, shares of
#: energy to 1e-6 (a ratio of two sums of squares of eigenvector entries).
TOLERANCES = (
    timing("seconds", "wall time of the section"),
    close("table[].*", rel=1e-8),
    close("bar[].fraction[]", rel=1e-12),
    close("bar[].ratio[]", rel=1e-8),
    close("bar[].omega_max", rel=1e-8),
    close("bar[].lattice", rel=1e-10),
    close("bar[].outlier_ratio", rel=1e-8),
    close("bar[].boundary_share", abs=1e-6),
    close("removal[].omega_max", rel=1e-8),
    close("removal[].gain", rel=1e-8),
    close("removal[].lattice", rel=1e-10),
    close("removal[].*low_error", rel=1e-6, abs=1e-12),
    unjudged("removal[].note", "the removal's parameter in words (its digits are judged "
             "through omega_max)"),
    close("removal_spectra[].*[]", rel=1e-8),
    close("strip[].ratio_*", rel=1e-8),
    close("strip[].omega_*", rel=1e-8),
    close("strip[].lattice", rel=1e-8),
    close("strip_spectra[].*[]", rel=1e-8),
    close("ring[].dt_*", rel=1e-8),
    close("ring[].omega_mesh", rel=1e-8),
    close("shapes[].omega", rel=1e-8),
    close("shapes[].mode[]", rel=1e-5, abs=1e-8),
    close("shapes[].x[]", rel=1e-12),
    unjudged("claims[].derived", "the derivation's digits, judged by the claim's status"),
)
FIGURES = ("finite_patches_spectra.png", "finite_patches_removal.png",
           "finite_patches_strip.png", "finite_patches_modes.png")


def _f(x, fmt=".4g") -> str:
    return "-" if x is None else format(x, fmt)


def _issue_table(data) -> str:
    n = data["settings"]["table_elements"]
    lines = ["| p, mass | lattice (periodic) | mesh, free ends | mesh, fixed ends | "
             "free: outliers, limit N -> inf | fixed: outliers, limit N -> inf |",
             "|---|---|---|---|---|---|"]
    for r in data["table"]:
        lines.append(f"| {r['p']} {r['mass']} | {r['lattice']:.3f} | {r['free']:.3f} | "
                     f"{r['fixed']:.3f} | {r['free_count']}, {_f(r['free_limit'], '.6f')} | "
                     f"{r['fixed_count']}, {_f(r['fixed_limit'], '.6f')} |")
    return (f"omega_max h / c of the bar, {n} elements (the mesh's proven upper bound, three "
            "digits; the lattice: the periodic bar's maximum over the zone; the limit: the "
            "semi-infinite end's boundary block, the largest outlier as N grows):\n\n"
            + "\n".join(lines))


def _outlier_tables(data) -> str:
    degrees = data["settings"]["degrees"]
    out = []
    for ends in ("free", "fixed"):
        rows = [r for r in data["bar"] if r["ends"] == ends]
        rules = list(dict.fromkeys(r["mass"] for r in rows))
        by = {(r["mass"], r["p"]): r for r in rows}
        lines = ["| rule | " + " | ".join(f"p = {p}" for p in degrees) + " |",
                 "|---|" + "---|" * len(degrees)]
        for m in rules:
            cells = []
            for p in degrees:
                r = by.get((m, p))
                cells.append("n/a" if r is None else
                             f"{r['count']}, x{r['outlier_ratio']:.3f}, "
                             f"{_f(r['boundary_share'], '.2f')} @ {r['peak']}")
            lines.append(f"| {m} | " + " | ".join(cells) + " |")
        out.append(f"**{ends} ends**\n\n" + "\n".join(lines))
    return ("Outliers of the bar, "
            f"{data['settings']['spectrum_elements']} elements, each cell: the frequencies "
            "above the lattice's largest, the mesh's largest over the lattice's "
            "(the lattice's step over the mesh's), the top mode's share of kinetic energy on "
            "the p functions at each end, and @ the distance of its largest coefficient from "
            "the nearest end (control points):\n\n" + "\n\n".join(out))


def _removal_table(data) -> str:
    k = data["settings"]["low_modes"]
    lines = ["| p | mass | ends | method | omega_max h/c (proven) | step gain | outliers | "
             f"error of the first {k} modes | plain mesh's | what the method did |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in data["removal"]:
        lines.append(f"| {r['p']} | {r['mass']} | {r['ends']} | {r['method']} | "
                     f"{r['omega_max']:.4f} | {_f(r.get('gain'), '.3f')} | {r['count']} | "
                     f"{r['low_error']:.2e} | {_f(r.get('plain_low_error'), '.2e')} | "
                     f"{r['note']} |")
    return "\n".join(lines)


def _strip_table(data) -> str:
    sizes = data["settings"]["strip_elements"]
    lines = ["| p | n | mass | ends | lattice omega_max H/c_T | "
             + " | ".join(f"mesh / lattice, N = {N}" for N in sizes) + " |",
             "|---|---|---|---|---|" + "---|" * len(sizes)]
    for r in data["strip"]:
        lines.append(f"| {r['p']} | {r['n']} | {r['mass']} | {r['ends']} | "
                     f"{_f(r.get('lattice'))} | "
                     + " | ".join(_f(r.get(f"ratio_{N}"), ".4f") for N in sizes) + " |")
    return "\n".join(lines)


def _ring_table(data) -> str:
    lines = ["| mass | mesh's proven stable step [s] | contact wing's estimate (massless held "
             "fixed) [s] | the scene's step [s] | scene / mesh |", "|---|---|---|---|---|"]
    for r in data["ring"]:
        lines.append(f"| {r['mass']} | {r['dt_mesh']:.5g} | {r['dt_held_fixed']:.5g} | "
                     f"{r['dt_scene']:g} | {r['dt_scene'] / r['dt_mesh']:.3f} |")
    if not data["ring"]:
        return ""
    r0 = data["ring"][0]
    return (f"The ring of the contact scene (level 0: {r0['elements'][0]} x "
            f"{r0['elements'][1]} elements, {r0['dofs']} DOFs, plane stress, at rest) as a "
            "mapped patch:\n\n" + "\n".join(lines))


def _claims(data) -> str:
    if not data["claims"]:
        return "(claims not verified in the quick run)"
    lines = ["| file | claim | status | derived |", "|---|---|---|---|"]
    for r in data["claims"]:
        lines.append(f"| {r['file']} | {r['claim']} | {r['status']} | {r['derived']} |")
    return "\n".join(lines)


def headline(data: dict) -> str:
    """One line: the p = 4 lumped free bar's step, plain and with the singular mass."""
    rows = [r for r in data["removal"] if r["mass"] == "lumped" and r["ends"] == "free"]
    if not rows:
        return "finite patches: no lumped free-ended bar measured"
    p = max(r["p"] for r in rows)
    by = {r["method"]: r for r in rows if r["p"] == p}
    plain = by.get("none")
    sing = next((r for m, r in by.items() if m.startswith("singular-lumped")), None)
    if plain is None or sing is None:
        return "finite patches: measured"
    return (f"finite patches: lumped bar p = {p}, free ends: omega_max h/c {plain['omega_max']:.3f} "
            f"on the open mesh, {sing['omega_max']:.3f} with the singular mass ({sing['method']}), "
            f"lattice {plain['lattice']:.3f}")


def _singular_words(data) -> str:
    rows = [r for r in data["removal"] if r["ends"] == "free" and r["mass"] == "lumped"]
    out = []
    for p in sorted({r["p"] for r in rows}):
        by = {r["method"]: r for r in rows if r["p"] == p}
        plain = by.get("none")
        for m, r in by.items():
            if m.startswith("singular") and plain is not None:
                out.append(f"p = {p} {m}: {plain['omega_max']:.3f} -> {r['omega_max']:.3f} "
                           f"(lattice {r['lattice']:.3f}, {r['count']} above it; first "
                           f"{data['settings']['low_modes']} modes {r['low_error']:.1e} against "
                           f"{plain['low_error']:.1e})")
    return "; ".join(out)


def render(data: dict, out: Path) -> str:
    """Figures and Markdown of the section, from the stored result."""
    from dispersion.plotting.finite_patches import (figure_bar_spectra, figure_outlier_modes,
                                                    figure_removal_spectra,
                                                    figure_strip_spectra)

    out = Path(out)
    save_figure(figure_bar_spectra(data), out / FIGURES[0], dpi=110)
    save_figure(figure_removal_spectra(data), out / FIGURES[1], dpi=110)
    save_figure(figure_strip_spectra(data), out / FIGURES[2], dpi=110)
    save_figure(figure_outlier_modes(data), out / FIGURES[3], dpi=110)
    fails = "".join(f"- not measured: {f}\n" for f in data["failures"])
    s = data["settings"]
    return (
        "## Finite patches: the mesh's own spectrum and step\n\n"
        "Every analysis above lives on the periodic lattice. A finite mesh with open knot "
        "vectors has boundary functions of short support whose frequencies (outliers) rise "
        "above the lattice's: its stable step of central differences is its own "
        "(`dispersion timestep --elements N --ends free`), proven here by a verified Cholesky "
        "factorization of sigma M - K (Rump 2006); the lattice's step holds for a periodic "
        "(or unbounded) mesh only.\n\n"
        + _issue_table(data) + "\n\n"
        "![normalized spectra](finite_patches_spectra.png)\n\n" + _outlier_tables(data)
        + "\n\n### Removing the outliers\n\nThree published methods "
          "(`removal=` of the finite patch; constraints: Hiemstra et al. 2021, Manni et al. "
          "2022; penalty: Deng and Calo 2021, weights ours; perturbation: after Nguyen et al. "
          "2022, our reading of its abstract) and the singular mass (the paper's rule at the "
          f"free ends, contact set = the end functions), on {s['spectrum_elements']} "
          "elements. Step gain: the plain mesh's largest frequency over the method's; error: "
          "the largest relative error of the first non-rigid frequencies against n pi / L.\n\n"
          "![removal](finite_patches_removal.png)\n\n" + _removal_table(data)
        + "\n\nThe singular mass at the free ends of the row-sum lumped bar: "
        + _singular_words(data) + ".\n\n"
        "### The plate strip\n\n![strip](finite_patches_strip.png)\n\n"
        "Largest frequency of the plane-strain strip over the Bloch patch's (same thickness "
        "mesh, rule and square elements), two mesh sizes:\n\n" + _strip_table(data)
        + "\n\n### The ring\n\n" + _ring_table(data)
        + "\n\n### Outlier modes\n\n![outlier modes](finite_patches_modes.png)\n\n"
        "### The papers' claims about finite meshes\n\n" + _claims(data) + "\n\n" + fails
        + f"\nMeasured in {data['seconds']:.0f} s. Data: `finite_patches.json`. Regenerate: "
          "`dispersion reproduce --sections finite_patches`.\n")
