"""Lamb and SH dispersion curves in the practitioner's units, and mode shapes through the plate.

Drawn from plain data: ``curves`` maps a mode label to arrays ``f`` (kHz), ``fd`` (MHz mm),
``c_p``, ``c_g`` (m/s) and ``k`` (rad/mm) ordered along the branch
(:meth:`dispersion.answers.mode_table.ModeTable.curves`,
:meth:`dispersion.answers.units.PhysicalBranches.curves`); ``zgv`` is a list of dicts with
``mode``, ``f [kHz]``, ``fd [MHz mm]``, ``c_p [m/s]``, ``wavelength [mm]``; ``cutoffs`` maps
labels to kHz. The title is the result's own (material, thickness, nu). S modes solid blue, A
dashed red, SH dotted green; ZGV points black circles, cut-offs triangles on the axis.

>>> import numpy as np
>>> c = {"S0": {"f": np.array([100.0, 200.0]), "fd": np.array([0.1, 0.2]),
...             "c_p": np.array([5400.0, 5390.0]), "c_g": np.array([5380.0, 5300.0]),
...             "k": np.array([0.1, 0.2])}}
>>> fig = figure_dispersion(c, "aluminium, d = 1 mm, nu = 0.3375")
>>> [ax.get_xlabel() for ax in fig.axes]
['fd [MHz mm]', 'fd [MHz mm]', 'f [kHz]']
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from dispersion.plotting import new_figure

__all__ = ["figure_dispersion", "figure_mode_fields", "figure_mode_shapes", "figure_mode_table",
           "plot_curves"]

_STYLE = {"S": ("C0", "-"), "A": ("C3", "--"), "SH": ("C2", ":")}
_PANELS = (("fd", "c_p", "fd [MHz mm]", "phase velocity c_p [m/s]"),
           ("fd", "c_g", "fd [MHz mm]", "group velocity c_g [m/s]"),
           ("f", "k", "f [kHz]", "wavenumber k [rad/mm]"))


def _family(label: str) -> str:
    return label.rstrip("0123456789?")


def plot_curves(curves: Mapping, x: str, y: str, ax=None, ymax: float | None = None,
                colour: str | None = None):
    """One line per mode of ``curves[label][y]`` against ``[x]``, labelled at its end (in its
    family's colour, or all in ``colour``)."""
    from dispersion.plotting import axes

    from dispersion.plotting.labels import place_labels

    ax = axes(ax)
    labels = []
    for label, d in curves.items():
        xs, ys = np.asarray(d[x], float), np.asarray(d[y], float)
        ok = np.isfinite(xs) & np.isfinite(ys)
        if ymax is not None:
            ys = np.where(ys <= ymax, ys, np.nan)
            ok &= np.isfinite(ys)
        if not np.any(ok):
            continue
        own, ls = _STYLE.get(_family(label), ("k", "-"))
        # a mode at one frequency (or one point left after the cap) is a point, not a line:
        # drawn as a marker, so a table at one frequency does not give empty panels
        alone = np.count_nonzero(ok) < 2
        ax.plot(xs, ys, color=colour or own, ls=ls, lw=1.1, marker="o" if alone else None,
                ms=4, mfc="none" if _family(label) == "A" else (colour or own))
        i = np.flatnonzero(ok)[-1] if y != "c_p" else np.flatnonzero(ok)[0]
        labels.append((xs[i], ys[i], label, colour or own))
    ax.autoscale_view()
    place_labels(ax, labels)  # apart where two modes end at one place (SH0 and A0, S0 and S1)
    return ax.figure


def figure_dispersion(curves: Mapping, title: str, zgv: Sequence[Mapping] = (),
                      cutoffs: Mapping | None = None, c_max: float | None = None,
                      discrete: Mapping | None = None):
    """Phase and group velocity against fd, wavenumber against f; ZGV and cut-offs marked.

    ``c_max`` caps the phase-velocity axis (it diverges at each cut-off); default: three
    times the largest group velocity drawn. ``discrete`` maps a legend name to ``(mass rule,
    curves)`` of discrete branches, drawn as markers in the rule's style
    (:func:`dispersion.plotting.styles.mass_style`).
    """
    fig = new_figure(figsize=(12.0, 4.0))
    axs = fig.subplots(1, 3)
    if c_max is None:
        cg = [np.nanmax(np.abs(d["c_g"])) for d in curves.values() if len(d["c_g"])]
        c_max = 3 * max(cg) if cg else None
    for ax, (x, y, xl, yl) in zip(axs, _PANELS):
        # beside discrete markers (coloured by mass rule) the exact curves are black
        plot_curves(curves, x, y, ax, ymax=c_max if y == "c_p" else None,
                    colour="k" if discrete else None)
        for name, (mass, dcurves) in (discrete or {}).items():
            _plot_markers(dcurves, x, y, ax, mass, name if y == "c_p" else None,
                          ymax=c_max if y == "c_p" else None)
        ax.set_xlabel(xl)
        ax.set_ylabel(yl)
        ax.set_xlim(left=0)
        if y != "c_g":  # a backward wave (S1 below its cut-off) has c_g < 0: keep it
            ax.set_ylim(bottom=0)
        else:
            ax.axhline(0.0, color="0.7", lw=0.6)
    fd_per_khz = _fd_per_khz(curves)
    for p in zgv:
        axs[1].plot(p["fd [MHz mm]"], 0.0, "o", mfc="none", color="k", ms=6, clip_on=False)
        axs[1].annotate(f"ZGV {p['mode']}", (p["fd [MHz mm]"], 0.0), fontsize=7,
                        xytext=(3, 6), textcoords="offset points")
        axs[0].plot(p["fd [MHz mm]"], p["c_p [m/s]"], "o", mfc="none", color="k", ms=6)
        axs[2].plot(p["f [kHz]"], 2 * np.pi / p["wavelength [mm]"], "o", mfc="none",
                    color="k", ms=6)
    xmax = max((np.nanmax(d["f"]) for d in curves.values() if len(d["f"])), default=None)
    for label, f_c in (cutoffs or {}).items():
        if xmax is None or f_c > xmax:
            continue
        colour = _STYLE.get(_family(label), ("k", "-"))[0]
        axs[2].plot(f_c, 0.0, "^", color=colour, ms=5, clip_on=False)
        if fd_per_khz is not None:
            axs[1].plot(f_c * fd_per_khz, 0.0, "^", color=colour, ms=5, clip_on=False)
    axs[2].plot([], [], "^", color="0.4", ms=5, label="cut-off")
    if zgv:
        axs[2].plot([], [], "o", mfc="none", color="k", ms=6, label="ZGV point")
    for fam, (colour, ls) in _STYLE.items():
        if any(_family(lab) == fam for lab in curves):
            axs[2].plot([], [], color="k" if discrete else colour, ls=ls,
                        label=f"{fam} modes" + (", exact" if discrete else ""))
    if discrete:  # the discrete sets' markers, once, beside the figure
        fig.legend(*axs[0].get_legend_handles_labels(), loc="outside lower center",
                   ncol=min(len(discrete), 3), fontsize="small")
    axs[2].legend(fontsize="small", loc="upper left")
    fig.suptitle(title, fontsize="medium")
    return fig


def _plot_markers(curves: Mapping, x: str, y: str, ax, mass, name: str | None,
                  ymax: float | None = None) -> None:
    """Discrete branches as markers in the style of their mass rule (S filled, A open)."""
    from dispersion.plotting.styles import mass_style

    style = mass_style(mass)
    first = True
    for label, d in curves.items():
        xs, ys = np.asarray(d[x], float), np.asarray(d[y], float)
        if ymax is not None:
            ys = np.where(ys <= ymax, ys, np.nan)
        every = max(1, xs.size // 40)
        ax.plot(xs[::every], ys[::every], ls="none", marker=style.marker, ms=3.2,
                color=style.colour, mfc=style.colour if label[0] == "S" else "none",
                label=f"{name} (S filled, A open)" if first and name else None)
        first = False


def _fd_per_khz(curves: Mapping) -> float | None:
    for d in curves.values():
        f, fd = np.asarray(d["f"], float), np.asarray(d["fd"], float)
        ok = np.isfinite(f) & np.isfinite(fd) & (f > 0)
        if np.any(ok):
            return float(fd[ok][0] / f[ok][0])
    return None


def figure_mode_fields(fields: Sequence[Mapping], title: str, panels: Sequence = (),
                       layers: Sequence = (), axis: str = "y [mm]"):
    """Displacements and stresses through the thickness, one column of panels per root.

    Each entry of ``fields`` has ``"name"`` (caption of the root), ``axis`` and any of
    the displacement (``u_*``) and stress (``sigma_*``) arrays. With ``panels`` (``(x
    label, keys)`` each): one row of panels per root, a panel per entry, a key ``Im ...``
    dashed in the colour of its ``Re ...``, fields that vanish left out; ``layers`` ``(name,
    z_bottom, z_top)``: the interfaces drawn as grey lines, each layer named at its middle.
    """
    n = len(fields)
    if panels:
        return _figure_panels(fields, title, panels, layers, axis)
    fig = new_figure(figsize=(4.2 * max(n, 1), 6.0))
    axs = np.atleast_2d(fig.subplots(2, max(n, 1), squeeze=False))
    for j, fl in enumerate(fields):
        y = fl[axis]
        for key, val in fl.items():
            if key.startswith("u_"):
                axs[0, j].plot(val, y, label=key)
            elif key.startswith("sigma_"):
                axs[1, j].plot(val, y, label=key)
        axs[0, j].set_title(fl["name"], fontsize="small")
        axs[0, j].set_xlabel("displacement / max |u|")
        axs[1, j].set_xlabel("stress / (mu max|u| / h)")
        for ax in axs[:, j]:
            ax.set_ylabel(axis)
            ax.axvline(0.0, color="0.7", lw=0.6)
            ax.legend(fontsize="small")
    fig.suptitle(title, fontsize="medium")
    return fig


def _figure_panels(fields, title, panels, layers, axis):
    n = len(fields)
    fig = new_figure(figsize=(3.4 * len(panels), 4.6 * max(n, 1)))
    axs = np.atleast_2d(fig.subplots(max(n, 1), len(panels), squeeze=False, sharey=True))
    for i, fl in enumerate(fields):
        z = np.asarray(fl[axis], float)
        for ax, (xlabel, keys) in zip(axs[i], panels):
            top = max((np.max(np.abs(fl[k])) for k in keys), default=0.0)
            colours = {}
            for key in keys:
                val = np.asarray(fl[key], float)
                if top == 0 or np.max(np.abs(val)) <= 1e-9 * top:
                    continue        # a field that vanishes (u2 of a Lamb mode)
                part, _, rest = key.partition(" ")
                name = rest.rsplit(" [", 1)[0] if part in ("Re", "Im") else key.rsplit(" [", 1)[0]
                first = name not in colours      # its first line drawn carries its name
                if first:
                    colours[name] = f"C{len(colours)}"
                ax.plot(val, z, color=colours[name], lw=1.1, ls="--" if part == "Im" else "-",
                        label=name if first else None)
            ax.set_xlabel(xlabel, fontsize="small")
            ax.axvline(0.0, color="0.7", lw=0.6)
            for _, lo, hi in layers[1:]:
                ax.axhline(lo, color="0.5", lw=0.8, ls=":")
            if ax.lines:
                ax.legend(fontsize="x-small", loc="best")
        axs[i, 0].set_ylabel(axis)
        axs[i, 0].set_title(fl["name"], fontsize="small", loc="left")
        for name, lo, hi in layers:
            axs[i, -1].annotate(name, (1.02, (lo + hi) / 2), xycoords=("axes fraction", "data"),
                                fontsize="x-small", va="center")
    fig.suptitle(title, fontsize="medium")
    return fig


def figure_mode_table(table):
    """The figure of a :class:`~dispersion.answers.mode_table.ModeTable`, titled from it."""
    return figure_dispersion(table.curves(), table.title(), table.zgv(), table.cutoffs_khz())


def figure_mode_shapes(shapes):
    """The figure of a :class:`~dispersion.answers.mode_shape_table.ModeShapeTable`."""
    return figure_mode_fields(shapes.figure_data(), shapes.title(), shapes.panels,
                              shapes.layers, shapes.axis)
