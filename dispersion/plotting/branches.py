"""Figures of the dispersion branches, drawn from plain data (lists and dicts as in JSON).

The data come from :mod:`dispersion.studies.branch_study` (``figure2_data``, ``measure_branches``).
Conventions shared by every figure: exact branches black, S solid and A dashed, labelled at
their ends; one colour per mass variant (consistent C0, singular C1, lumped C2) in every
panel; errors signed on a symmetric-log axis; values at round-off level (below
``ROUND_OFF``) are not drawn as data.

>>> import numpy as np
>>> ax = plot_exact([0.0, 1.0, 2.0], {"S0": [0.0, 1.6, 2.5], "A0": [0.0, 0.6, 1.6]}, 3.0)
>>> ax.get_xlabel()
'$\\\\kappa = kh$'
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from dispersion.plotting import axes

__all__ = [
    "MASS_COLOURS",
    "figure2",
    "figure_per_wavelength",
    "figure_shapes",
    "figure_speed_accuracy",
    "figure_velocities",
    "plot_discrete",
    "plot_exact",
    "plot_paired_errors",
    "plot_speed_accuracy",
    "plot_zone_edge",
]

MASS_COLOURS = {"consistent": "C0", "singular": "C1", "lumped": "C2", "singular-lumped": "C3"}
ROUND_OFF = 1e-13
_BRANCH_STYLE = {"S0": "-", "A0": "--", "S1": "-.", "A1": ":"}


def _axes(ax):
    return axes(ax, (5.5, 4.0))


def _a(values) -> np.ndarray:
    return np.array([np.nan if v is None else v for v in values], dtype=float)


def _colour(name: str, i: int = 0) -> str:
    return MASS_COLOURS.get(name, f"C{4 + i}")


def _label_mode(ax, x, y, label, ymax, color="k"):
    """Mode label: at the cut-off (left end) for higher modes, at the right end for S0/A0."""
    ok = np.flatnonzero(np.isfinite(y) & (y <= ymax))
    if ok.size == 0:
        return
    i = ok[-1] if label[1:] == "0" else ok[0]
    up = 5 if label[0] == "S" else -5  # S0/A0 meet at the Rayleigh line: S above, A below
    dx = (-3, up) if label[1:] == "0" else (3, 0.8 * up)
    ax.annotate(label, (x[i], y[i]), xytext=dx, textcoords="offset points",
                fontsize="x-small", color=color, va="center",
                ha="right" if label[1:] == "0" else "left", clip_on=True)


def plot_exact(kappa, omega: Mapping, omega_max: float, ax=None,
               label: str = "exact Rayleigh-Lamb (S solid, A dashed)"):
    """Exact branches ``omega[label]`` on ``kappa``: black, S solid, A dashed, labelled."""
    ax = _axes(ax)
    kappa = _a(kappa)
    first = True
    for name, w in omega.items():
        w = _a(w)
        ax.plot(kappa, w, color="k", lw=1.1, ls="-" if name[0] == "S" else "--",
                label=label if first else None)
        _label_mode(ax, kappa, w, name, omega_max)
        first = False
    ax.set_xlabel(r"$\kappa = kh$")
    ax.set_ylabel(r"$\Omega = \omega h / c_T$")
    ax.set_ylim(0, omega_max)
    return ax


def plot_discrete(kappa, omega: Mapping, symmetry: Mapping, ax=None, name: str = "discrete",
                  color: str = "C0", marker: str = "o", every: int | None = None):
    """Discrete branches as markers (S filled, A open; "mixed" parity said in the label)."""
    ax = _axes(ax)
    kappa = _a(kappa)
    every = every or max(1, kappa.size // 40)
    mixed = "mixed" in symmetry.values()
    note = (" (S filled, A open, by dominant parity: the mass breaks the mirror)" if mixed
            else " (S filled, A open)")
    first = True
    for lab, w in omega.items():
        w = _a(w)
        ax.plot(kappa[::every], w[::every], ls="none", marker=marker, ms=3.2, color=color,
                mfc=color if lab[0] == "S" else "none", label=name + note if first else None)
        first = False
    return ax


def plot_zone_edge(edge: float, ax=None):
    """Vertical line at the Brillouin-zone edge pi/r, with the folding stated."""
    ax = _axes(ax)
    ax.axvline(edge, color="0.5", lw=0.9, ls=":")
    ax.annotate(r"zone edge $\pi/r$: beyond it, folded Bloch branches", (edge, 0.98),
                xycoords=("data", "axes fraction"), rotation=90, ha="right", va="top",
                fontsize="x-small", color="0.35")
    return ax


def _symlog(ax, linthresh: float, what: str):
    ax.axhline(0.0, color="0.4", lw=0.7)
    ax.set_yscale("symlog", linthresh=linthresh)
    ax.set_ylabel(f"{what} (signed; symlog, linear below {linthresh:.0e})")


def plot_paired_errors(kappa, errors: Mapping, ax=None, name: str = "", color: str = "C0",
                       branches: Sequence[str] = ("S0", "A0", "S1", "A1"),
                       linthresh: float = 1e-8):
    """Signed relative error of each exact branch against its shape partner, symlog axis."""
    ax = _axes(ax)
    kappa = _a(kappa)
    for b in branches:
        if b not in errors:
            continue
        e = _a(errors[b])
        e[np.abs(e) < ROUND_OFF] = np.nan  # round-off, not data
        if np.any(np.isfinite(e) & (kappa > 0)):
            ax.plot(kappa, e, _BRANCH_STYLE.get(b, "-"), color=color, lw=1.2,
                    label=f"{name} {b}".strip())
    ax.set_xscale("log")
    ax.set_xlabel(r"$\kappa = kh$")
    _symlog(ax, linthresh, r"$(\Omega^h - \Omega)/\Omega$")
    return ax


def figure2(data: Mapping, title: str = ""):
    """Figure 2 (right) of the paper plus the signed, shape-paired error panel.

    ``data``: :func:`dispersion.studies.branch_study.figure2_data` (or the stored JSON of it).
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(12, 5.2), layout="constrained")
    ax, ax_err = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.25, 1]})
    kappa = data["kappa"]
    plot_exact(kappa, {k: v["omega"] for k, v in data["exact"].items()}, data["omega_max"], ax)
    for i, (name, d) in enumerate(data["discrete"].items()):
        plot_discrete(kappa, d["omega"], d["symmetry"], ax, name, _colour(name, i), "os^v"[i % 4])
        plot_paired_errors(kappa, d["paired_error"], ax_err, name, _colour(name, i))
    edges = {d["zone_edge"] for d in data["discrete"].values() if d["zone_edge"] is not None}
    for edge in edges:
        plot_zone_edge(edge, ax)
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=3,
               fontsize="small")
    if ax_err.get_legend_handles_labels()[0]:
        ax_err.legend(fontsize="x-small", ncol=2)
    ax_err.set_title("error of each exact branch against the discrete mode of the same shape\n"
                     "(MAC >= 0.5; no curve: no discrete mode resembles it)", fontsize="small")
    if title:
        ax.set_title(title, fontsize="small")
    return fig


def figure_velocities(data: Mapping, discrete: str = "consistent", fd_per_omega=None,
                      zgv: Sequence[Mapping] = ()):
    """Phase and group velocity (over c_T) against Omega: exact lines, discrete markers, ZGV."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(12, 4.6), layout="constrained")
    ax_p, ax_g = fig.subplots(1, 2)
    wmax = data["omega_max"]
    for lab, v in data["exact"].items():
        w = _a(v["omega"])
        ls = "-" if lab[0] == "S" else "--"
        for ax, key in ((ax_p, "phase"), (ax_g, "group")):
            y = _a(v[key])
            ax.plot(w, y, color="k", lw=1.0, ls=ls,
                    label="exact Rayleigh-Lamb (S solid, A dashed)" if lab == "S0" else None)
    for lab in data["exact"]:
        w, cp = _a(data["exact"][lab]["omega"]), _a(data["exact"][lab]["phase"])
        ok = np.flatnonzero(np.isfinite(cp) & (cp < 4) & (w < wmax))
        if ok.size:
            ax_p.annotate(lab, (w[ok[-1]], cp[ok[-1]]), fontsize="x-small", textcoords="offset points",
                          xytext=(2, 2) if lab[1:] != "0" else (-12, 5 if lab[0] == "S" else -10))
    d = data["discrete"].get(discrete)
    if d is not None:
        # folded Bloch branches (beyond the zone edge) have no exact counterpart: not drawn
        inside = _a(data["kappa"]) <= (d["zone_edge"] if d["zone_edge"] is not None else np.inf)
        for lab, g in d["group"].items():
            w = np.where(inside, _a(d["omega"][lab]), np.nan)
            every = max(1, w.size // 60)
            ax_g.plot(w[::every], _a(g)[::every], ls="none", marker="o", ms=2.5,
                      color=_colour(discrete), mfc=_colour(discrete) if lab[0] == "S" else "none",
                      label=f"{discrete} mass, eigenvector formula (first zone)"
                      if lab == "S0" else None)
    for z in zgv:
        ax_g.plot(z["omega"], 0.0, "r*", ms=9)
        ax_g.annotate(f"ZGV {z['label']}", (z["omega"], 0.0), xytext=(3, -12),
                      textcoords="offset points", fontsize="x-small", color="r")
    ax_p.set_ylim(0, 4)
    ax_g.set_ylim(-1.0, 2.0)
    ax_g.axhline(0.0, color="0.6", lw=0.7)
    for ax, what in ((ax_p, r"phase velocity $c_p / c_T = \Omega/\kappa$"),
                     (ax_g, r"group velocity $c_g / c_T = d\Omega/d\kappa$")):
        ax.set_xlim(0, wmax)
        ax.set_xlabel(r"$\Omega = \omega h / c_T$")
        ax.set_ylabel(what)
        if fd_per_omega:
            top = ax.secondary_xaxis("top", functions=(lambda x: x * fd_per_omega,
                                                       lambda x: x / fd_per_omega))
            top.set_xlabel(r"fd [MHz mm] $= \Omega c_T / \pi$ for $c_T$ = 3130 m/s",
                           fontsize="small")
    ax_g.legend(fontsize="x-small", loc="lower right")
    return fig


def figure_per_wavelength(per_wavelength: Mapping, bar: Mapping):
    """Signed relative phase-velocity error against elements per wavelength: plate S0, A0, bar."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(13, 4.4), layout="constrained")
    axs = fig.subplots(1, 3, sharey=True)
    epw = _a(per_wavelength["elements_per_wavelength"])
    styles = {1: ":", 2: "-", 3: "--", 4: "-."}
    for ax, branch in zip(axs[:2], ("S0", "A0")):
        for c in per_wavelength["curves"]:
            if c["branch"] != branch:
                continue
            e = _a(c["error"])
            e[np.abs(e) < ROUND_OFF] = np.nan
            ax.plot(epw, e, styles[c["p"]], color=_colour(c["mass"]),
                    label=f"p = {c['p']} (n = {c['n']}), {c['mass']}")
        ax.set_title(f"plate {branch}, Bloch patch r = b/h = {per_wavelength['r']:g}",
                     fontsize="small")
    x = _a(bar["elements_per_wavelength"])
    for key, e in bar["error"].items():
        p, mass = int(key.split()[0][2:]), key.split()[1]
        e = _a(e)
        e[np.abs(e) < ROUND_OFF] = np.nan
        axs[2].plot(x, e, styles[p], color=_colour(mass), label=f"p = {p}, {mass}")
    axs[2].set_title("1D bar, periodic B-splines (Cottrell et al. 2006)", fontsize="small")
    for ax in axs:
        ax.set_xscale("log")
        ax.set_xlabel("elements per wavelength")
        ax.axhline(0.0, color="0.4", lw=0.7)
        ax.set_yscale("symlog", linthresh=1e-12)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize="xx-small", ncol=1)
    axs[0].set_ylabel(r"$c_p^h / c_p - 1 = \Omega^h/\Omega - 1$ (symlog, linear below 1e-12)")
    return fig


def figure_shapes(shapes: Mapping):
    """Exact (lines) and discrete (markers) through-thickness mode shapes with their MAC."""
    from matplotlib.figure import Figure

    modes = shapes["modes"]
    fig = Figure(figsize=(3.0 * len(modes), 3.6), layout="constrained")
    y = _a(shapes["y"])
    for ax, m in zip(fig.subplots(1, len(modes), sharey=True, squeeze=False).ravel(), modes):
        for comp, (col, name) in enumerate((("C0", "$U_x$"), ("C3", "$U_y$"))):
            ax.plot(_a(m["exact"][comp]), y, color=col, lw=1.2, label=f"{name} exact")
            ax.plot(_a(m["discrete"][comp])[::4], y[::4], "o", color=col, mfc="none", ms=4,
                    label=f"{name} patch")
        ax.axvline(0.0, color="0.7", lw=0.6)
        ax.set_title(f"{m['label']}: $\\Omega$ = {m['omega']:.4f} ({m['omega_h']:.4f})\n"
                     f"MAC = {m['mac']:.4f}", fontsize="small")
        ax.set_xlabel("displacement (unit norm)")
    fig.axes[0].set_ylabel("$y / h$")
    fig.axes[0].legend(fontsize="xx-small")
    fig.suptitle(f"mode shapes at $\\kappa$ = {shapes['kappa']:g}: exact (lines) and the "
                 "consistent-mass patch, p = 2, n = 3 (markers; its Omega in brackets)",
                 fontsize="small")
    return fig


def plot_speed_accuracy(rows: Sequence[Mapping], ax=None, label=None, floor: float | None = None,
                        order=None):
    """Error against wall time, one line per group of ``rows`` (``label(row)`` names it),
    points joined in the order of ``order(row)`` (default: time).

    Errors below ``floor`` (the reference's own accuracy) carry no information: they are
    drawn at the floor as open markers.
    """
    ax = _axes(ax)
    label = label or (lambda r: str(r.get("name", "")))
    groups: dict[str, list] = {}
    for row in rows:
        groups.setdefault(label(row), []).append(row)
    for i, (name, rs) in enumerate(groups.items()):
        rs = sorted(rs, key=order or (lambda r: r["time_s"]))
        t = np.array([r["time_s"] for r in rs])
        e = np.array([np.nan if r["error"] is None else r["error"] for r in rs])
        lo = floor if floor else 0.0
        below = e <= lo
        ax.loglog(t, np.where(below, lo, e), "-", color=f"C{i}", label=name)
        ax.loglog(t[~below], e[~below], "o", color=f"C{i}")
        if below.any():
            ax.loglog(t[below], np.full(below.sum(), lo), "o", color=f"C{i}", mfc="none")
    if floor:
        ax.axhline(floor, color="0.4", lw=0.8, ls=":",
                   label="reference's own error (open markers: at or below it)")
    from matplotlib.ticker import NullFormatter

    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("wall time [s]")
    ax.legend(fontsize="x-small")
    return ax


def figure_speed_accuracy(tracer: Mapping, discrete_rows: Sequence[Mapping]):
    """Tracer (per scan step) and discrete solver (per p and mass) speed/accuracy panels."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11, 4.2), layout="constrained")
    a1, a2 = fig.subplots(1, 2)
    ref = tracer["reference"]
    plot_speed_accuracy(tracer["rows"], a1, label=lambda r: "exact tracer",
                        floor=tracer["reference_mpmath_error"], order=lambda r: -r["rtol"])
    a1.set_title(f"Rayleigh-Lamb tracer, {tracer['kappa_count']} kappa, Omega <= "
                 f"{tracer['omega_max']:g}; points: rtol\nerror vs reference (rtol {ref[1]:g}; "
                 f"rtol falls along the line), itself vs 40-digit mpmath: "
                 f"{tracer['reference_mpmath_error']:.1e}", fontsize="small")
    a1.set_ylabel("max relative error of the roots")
    plot_speed_accuracy(discrete_rows, a2, label=lambda r: f"p = {r['p']}, {r['mass']}",
                        order=lambda r: r["n"])
    a2.set_title("discrete branches (points: n = p+1, p+3 control points)",
                 fontsize="small")
    a2.set_ylabel("max |relative error| S0/A0, kappa <= 1")
    return fig
