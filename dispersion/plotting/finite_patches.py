"""Figures of the finite patches (:mod:`dispersion.studies.finite_patches`), from stored data.

Every function takes the stored result (plain JSON) and returns a figure of several panels;
nothing is computed here but the layout.
"""
from __future__ import annotations

__all__ = ["figure_bar_spectra", "figure_removal_spectra", "figure_strip_spectra",
           "figure_outlier_modes"]

_STYLES = ("-", "--", "-.", ":")


def _figure(rows: int, cols: int, size):
    from dispersion.plotting import new_figure

    fig = new_figure(figsize=size)
    return fig, fig.subplots(rows, cols, squeeze=False, sharex=True)


def figure_bar_spectra(data: dict):
    """omega_h^n / omega^n against n/N: a panel per (ends, p), a line per rule."""
    rows = data["bar"]
    degrees = data["settings"]["degrees"]
    ends = ("free", "fixed")
    fig, ax = _figure(len(ends), len(degrees), (3.3 * len(degrees), 6.4))
    rules = list(dict.fromkeys(r["mass"] for r in rows))
    colours = {m: f"C{i % 10}" for i, m in enumerate(rules)}
    styles = {m: _STYLES[(i // 10) % len(_STYLES)] for i, m in enumerate(rules)}
    top = max((max(r["ratio"]) for r in rows if r["ratio"]), default=2.0)
    for i, e in enumerate(ends):
        for j, p in enumerate(degrees):
            a = ax[i][j]
            for r in rows:
                if r["ends"] == e and r["p"] == p:
                    a.plot(r["fraction"], r["ratio"], color=colours[r["mass"]],
                           ls=styles[r["mass"]], lw=1.1, label=r["mass"])
            a.axhline(1.0, color="k", lw=0.5)
            a.set_ylim(0.0, min(top * 1.05, 4.2))
            a.set_title(f"p = {p}, {e} ends", fontsize="small")
            a.grid(True, lw=0.3, alpha=0.5)
            if i == len(ends) - 1:
                a.set_xlabel("n / N")
            if j == 0:
                a.set_ylabel(r"$\omega_h^n / \omega^n$")
    handles, labels = ax[0][-1].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=min(7, len(labels)),
               fontsize="x-small")
    fig.suptitle(f"Normalized spectra of the bar, {data['settings']['spectrum_elements']} "
                 "elements, open knot vectors (the closed form n pi / L as reference)",
                 fontsize="small")
    return fig


def figure_removal_spectra(data: dict):
    """The outlier-removal methods (and the singular mass) at the top degree, free ends."""
    rows = data["removal_spectra"]

    def title(mass):
        p = next(r["p"] for r in rows if r["mass"] == mass)
        return f"p = {p}, {mass} mass, free ends"

    return _ratios_by_mass(rows, title, r"$\omega_h^n / \omega^n$",
                           lambda k, r: (f"C{k}", r["method"]))


def figure_strip_spectra(data: dict):
    """The strip with sliding ends against the Rayleigh-Lamb modes, a line per p and mass."""
    return _ratios_by_mass(
        data["strip_spectra"], lambda mass: f"plate strip, sliding ends, {mass} mass",
        r"$\omega_h^n / \omega^n$ (Rayleigh-Lamb at $\kappa = m\pi H/L$)",
        lambda k, r: (f"C{r['p'] - 1}", f"p = {r['p']}, n = {r['n']}"))


def _ratios_by_mass(rows, title, ylabel, line):
    """One panel per mass of normalized spectra (``line(k, row)``: its colour and label)."""
    masses = list(dict.fromkeys(r["mass"] for r in rows))
    fig, ax = _figure(1, len(masses), (5.2 * len(masses), 4.0))
    for j, mass in enumerate(masses):
        a = ax[0][j]
        for k, r in enumerate(x for x in rows if x["mass"] == mass):
            color, label = line(k, r)
            a.plot(r["fraction"], r["ratio"], color=color, lw=1.2, label=label)
        a.axhline(1.0, color="k", lw=0.5)
        a.set_title(title(mass), fontsize="small")
        a.set_xlabel("n / N")
        a.set_ylabel(ylabel)
        a.grid(True, lw=0.3, alpha=0.5)
        a.legend(fontsize="x-small")
    return fig


def figure_outlier_modes(data: dict):
    """The top modes of the bar (control-point values at the Greville points)."""
    rows = data["shapes"]
    masses = list(dict.fromkeys(r["mass"] for r in rows))
    fig, a2 = _figure(1, len(masses), (5.2 * len(masses), 3.6))
    for j, mass in enumerate(masses):
        a = a2[0][j]
        for r in (x for x in rows if x["mass"] == mass):
            a.plot(r["x"], r["mode"], marker="o", ms=2.5, lw=0.9,
                   label=f"mode N - {r['rank'] - 1}: omega h/c = {r['omega']:.4g}")
        a.set_title(f"outlier modes, p = {rows[0]['p']}, {mass} mass, free ends",
                    fontsize="small")
        a.set_xlabel("x / h (Greville abscissae)")
        a.set_ylabel("control-point value (max 1)")
        a.grid(True, lw=0.3, alpha=0.5)
        a.legend(fontsize="x-small")
    return fig
