"""Figures of the studies beyond the paper (:mod:`dispersion.report.studies`).

Each ``plot_*`` takes the study's plain data (lists/dicts as stored in ``studies.json``) and
``ax=None``, and returns its Figure; ``figure_*`` lay several out on one pyplot-free
:class:`matplotlib.figure.Figure`.

>>> rows = [{"gamma_s": g, "S0": {"4": -g}, "A0": {"6": g}, "S0_error": [g / 10],
...          "A0_error": [g / 20]} for g in (0.0, 0.5, 1.0)]
>>> fig = figure_gamma(rows, kappas=[0.5])
>>> len(fig.axes)
2
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from dispersion.plotting import axes, new_figure


def _axes(ax):
    return axes(ax, (5, 3.5))


def plot_gamma_coefficients(rows: Sequence[dict], ax=None, exact: dict | None = None):
    """Leading error-carrying coefficients of Omega^2 against gamma_s (S0 k^4, A0 k^6), with
    the exact Rayleigh-Lamb coefficient of the same power as a horizontal reference line."""
    ax = _axes(ax)
    g = [row["gamma_s"] for row in rows]
    for i, (branch, power, style) in enumerate((("S0", "4", "o-"), ("A0", "6", "s--"))):
        vals = [row[branch].get(power, np.nan) for row in rows]
        ax.plot(g, vals, style, color=f"C{i}",
                label=f"{branch}: coefficient of $\\kappa^{power}$")
        if exact and power in exact.get(branch, {}):
            ax.axhline(exact[branch][power], color=f"C{i}", lw=1.0, ls=":",
                       label=f"{branch}, exact Rayleigh-Lamb: {exact[branch][power]:.4g}")
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel(r"redistribution weight $\gamma_s$")
    ax.set_ylabel(r"coefficient of $\Omega^2$ series")
    ax.legend(fontsize="small")
    return ax.figure


def plot_gamma_errors(rows: Sequence[dict], kappas: Sequence[float], ax=None):
    """Signed relative error of the S0 and A0 frequencies against gamma_s, one line per kappa.

    Signed, on a symmetric-log axis: an |error| axis would show a sign change as a fake
    optimum. One colour per kappa, one line style per branch.
    """
    ax = _axes(ax)
    g = [row["gamma_s"] for row in rows]
    floor = 1e-6
    for i, k in enumerate(kappas):
        for branch, style in (("S0", "o-"), ("A0", "s--")):
            err = [np.nan if row[f"{branch}_error"][i] is None else row[f"{branch}_error"][i]
                   for row in rows]
            ax.plot(g, err, style, color=f"C{i}", label=f"{branch}, $\\kappa$ = {k}")
    ax.axhline(0.0, color="0.4", lw=0.8)
    ax.set_yscale("symlog", linthresh=floor)
    ax.set_xlabel(r"redistribution weight $\gamma_s$")
    ax.set_ylabel(r"$(\Omega^h - \Omega) / \Omega$ (symlog, linear below $10^{-6}$)")
    ax.legend(fontsize="small")
    return ax.figure


def figure_gamma(rows: Sequence[dict], kappas: Sequence[float], exact: dict | None = None,
                 nu: float | None = None, r=None):
    """Two panels: series coefficients (exact ones as reference lines) and branch errors
    against gamma_s."""
    fig = new_figure(figsize=(10, 4.0))
    left, right = fig.subplots(1, 2)
    plot_gamma_coefficients(rows, ax=left, exact=exact)
    plot_gamma_errors(rows, kappas, ax=right)
    what = gamma_patch_text(rows)
    where = ", ".join(x for x in (f"nu = {nu:g}" if nu is not None else "",
                                  f"Bloch r = b/h = {r:g}" if r is not None and what is None
                                  else "") if x)
    what = what or "singular mass (patch not recorded in this older result)"
    fig.suptitle(what[:1].upper() + what[1:]
                 + r": effect of the redistribution weight $\gamma_s$"
                 + (f" ({where})" if where else ""), fontsize="medium")
    return fig


def gamma_patch_text(rows: Sequence[dict]) -> str | None:
    """The patch of the gamma_s study but its weight, from the patches its rows stored:
    ``singular mass (contact top), Bloch r = b/h = 2, p = 2, n = 3`` (None in older records)."""
    if not rows or not all(row.get("patch") for row in rows):
        return None
    from dispersion.symbolic.patch import Patch

    specs = [Patch.from_dict(row["patch"]) for row in rows]
    return " / ".join(dict.fromkeys(f"{sp.mass_name} mass (contact {sp.contact}), "
                                    f"{sp.geometry_title()}" for sp in specs))


def plot_series_departure(data: dict, branch: str, ax=None):
    """Relative deviation of truncated series from the numeric branch against kappa."""
    ax = _axes(ax)
    kappa = np.asarray(data["kappa_grid"])
    styles = {"exact": "-", "consistent": "--", "singular": ":"}
    for row in data["radius"]:
        if row["branch"] != branch:
            continue
        # below 1e-13 the deviation is round-off of the comparison: not drawn as data
        dev = np.asarray([np.nan if v is None else v for v in row["deviation"]], dtype=float)
        dev[~(dev > 1e-13)] = np.nan
        # colour: truncation order; line style: whose series (same meaning in both panels)
        ax.loglog(kappa, dev, styles.get(row["mass"], "-."),
                  color={4: "C0", 6: "C1", 8: "C2"}.get(row["order"], "C3"),
                  label=f"{row['mass']}, to $\\kappa^{{{row['order']}}}$")
    ax.axhline(data["tol"], color="k", lw=0.8, label=f"tolerance {data['tol']:g}")
    ax.set_xlabel(r"$\kappa = kh$")
    ax.set_ylabel(r"$|\Omega_{series} - \Omega| / \Omega$")
    ax.set_title(f"{branch}: truncated series vs numeric branch")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize="x-small", ncol=2)
    return ax.figure


def figure_radius(data: dict):
    """Two panels (S0, A0) of :func:`plot_series_departure`."""
    fig = new_figure(figsize=(10, 4))
    for ax, branch in zip(fig.subplots(1, 2), ("S0", "A0")):
        plot_series_departure(data, branch, ax=ax)
    return fig
