"""Figures of the dispersion branches (:mod:`dispersion.branches`, :mod:`dispersion.rayleigh_lamb`).

``plot_*`` take result objects and ``ax=None`` and return the Axes; :func:`figure2` lays out
the paper's Figure 2 (right) with an error panel on a pyplot-free Figure.

>>> import numpy as np
>>> from dispersion.rayleigh_lamb import trace_branches
>>> ax = plot_exact(trace_branches(0.3, np.linspace(0, 2, 5), 3.0))
>>> ax.get_xlabel()
'$\\\\kappa = kh$'
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from . import axes

__all__ = [
    "figure2",
    "plot_discrete",
    "plot_errors",
    "plot_exact",
    "plot_speed_accuracy",
    "plot_zone_edge",
]


def _axes(ax):
    return axes(ax, (5.5, 4.0))


def plot_exact(exact, ax=None, color="k", label="exact Rayleigh-Lamb (S solid, A dashed)"):
    """Exact branches: S solid, A dashed, one legend entry."""
    ax = _axes(ax)
    first = True
    for name, w in exact.omega.items():
        ax.plot(exact.kappa, w, color=color, lw=1.2, ls="-" if name[0] == "S" else "--",
                label=label if first else None)
        first = False
    ax.set_xlabel(r"$\kappa = kh$")
    ax.set_ylabel(r"$\Omega = \omega h / c_T$")
    ax.set_ylim(0, exact.omega_max)
    return ax


def plot_discrete(discrete, ax=None, color="C0", label="discrete", marker="o", every=None):
    """Discrete branches as markers (S filled, A open); ``mixed`` symmetry noted in the label."""
    ax = _axes(ax)
    every = every or max(1, discrete.kappa.size // 40)
    mixed = "mixed" in discrete.symmetry.values()
    first = True
    for name, w in discrete.omega.items():
        filled = name[0] == "S"
        ax.plot(discrete.kappa[::every], w[::every], ls="none", marker=marker, ms=3.5,
                color=color, mfc=color if filled else "none",
                label=(label + (" (S filled, A open; by dominant parity, the mass breaks "
                                "the mirror)" if mixed else " (S filled, A open)"))
                if first else None)
        first = False
    if discrete.zone_edge is not None:
        plot_zone_edge(discrete.zone_edge, ax)
    return ax


def plot_zone_edge(edge: float, ax=None):
    """Vertical line at the Brillouin-zone edge pi/r, with the folding stated."""
    ax = _axes(ax)
    if not any(getattr(line, "_zone_edge", False) for line in ax.lines):
        line = ax.axvline(edge, color="0.5", lw=0.9, ls=":")
        line._zone_edge = True
        ax.annotate(r"zone edge $\pi/r$; beyond it: folded Bloch branches", (edge, 0.98),
                    xycoords=("data", "axes fraction"), rotation=90, ha="right", va="top",
                    fontsize="x-small", color="0.35")
    return ax


def plot_errors(kappa, errors: Mapping[str, np.ndarray], ax=None, prefix: str = "",
                styles: Sequence[str] = ("-", "--", "-.", ":")):
    """Relative error of each discrete branch against its exact partner, log-log."""
    ax = _axes(ax)
    kappa = np.asarray(kappa)
    for i, (name, e) in enumerate(sorted(errors.items())):
        ok = (kappa > 0) & np.isfinite(e) & (e > 0)
        if ok.any():
            ax.loglog(kappa[ok], e[ok], styles[i % len(styles)], label=f"{prefix}{name}")
    ax.set_xlabel(r"$\kappa = kh$")
    ax.set_ylabel(r"$|\Omega^h - \Omega| / \Omega$")
    return ax


def figure2(exact, discretes: Sequence[tuple[str, object, Mapping]], title: str = ""):
    """Figure 2 (right) of the paper plus an error panel.

    ``discretes``: ``(name, DiscreteBranches, errors)`` triples, e.g. CMM and singular mass.
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11, 5.0), layout="constrained")
    ax, ax_err = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.3, 1]})
    plot_exact(exact, ax)
    for i, (name, d, errors) in enumerate(discretes):
        plot_discrete(d, ax, color=f"C{i}", label=name, marker="os^v"[i % 4])
        # the exact partner of a Bloch branch exists only inside the first zone
        inside = d.kappa <= (d.zone_edge if d.zone_edge is not None else np.inf)
        plot_errors(d.kappa[inside], {k: v[inside] for k, v in errors.items()
                                      if k in ("S0", "A0", "A1")}, ax_err, prefix=f"{name} ")
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=3,
               fontsize="small")
    ax_err.legend(fontsize="x-small", ncol=2)
    ax_err.set_title("error against the exact partner branch", fontsize="small")
    if title:
        ax.set_title(title, fontsize="small")
    return fig


def plot_speed_accuracy(rows: Sequence[Mapping], ax=None, x="time_s", y="error",
                        group="name"):
    """Error against cost, one line per ``group`` (rows: dicts with x, y and group keys)."""
    ax = _axes(ax)
    groups: dict[str, list] = {}
    for row in rows:
        groups.setdefault(str(row[group]), []).append(row)
    for name, rs in groups.items():
        rs = sorted(rs, key=lambda r: r[x])
        ax.loglog([r[x] for r in rs], [max(r[y], 1e-17) for r in rs], "o-", label=name)
    from matplotlib.ticker import NullFormatter

    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel({"time_s": "wall time [s]"}.get(x, x))
    ax.set_ylabel({"error": "max relative error"}.get(y, y))
    ax.legend(fontsize="x-small")
    return ax
