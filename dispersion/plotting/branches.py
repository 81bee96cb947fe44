"""Figures of the dispersion branches, drawn from plain data (lists and dicts as in JSON).

The data come from :mod:`dispersion.studies.branch_study` (``figure2_data``, ``measure_branches``).
Conventions shared by every figure: exact branches black, S solid and A dashed, labelled at
their ends; one colour and marker per mass rule in every panel, from the rule registry
(:func:`dispersion.plotting.styles.mass_style`); errors signed on a symmetric-log axis; values at round-off level (below
``ROUND_OFF``) are not drawn as data.

>>> import numpy as np
>>> fig = plot_exact([0.0, 1.0, 2.0], {"S0": [0.0, 1.6, 2.5], "A0": [0.0, 0.6, 1.6]}, 3.0)
>>> fig.axes[0].get_xlabel()
'$\\\\kappa = kh$'
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from dispersion.plotting import axes, new_figure

__all__ = [
    "figure2",
    "figure_branch_table",
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

ROUND_OFF = 1e-13
_BRANCH_STYLE = {"S0": "-", "A0": "--", "S1": "-.", "A1": ":"}


def _axes(ax):
    return axes(ax, (5.5, 4.0))


def _a(values) -> np.ndarray:
    return np.array([np.nan if v is None else v for v in values], dtype=float)


def _colour(name: str, i: int = 0) -> str:
    from dispersion.plotting.styles import mass_style

    return mass_style(name).colour


def _marker(name: str) -> str:
    from dispersion.plotting.styles import mass_style

    return mass_style(name).marker


#: Labels whose anchors lie closer than this fraction of the Omega axis form a group whose
#: lowest label goes below its curve and highest above (the rest are moved along the curve).
LABEL_GAP = 0.04


def _label_anchors(x, omega: Mapping, ymax: float) -> list[tuple[float, float, str, int]]:
    """Where each mode is labelled: the cut-off (left end) for higher modes, the right end
    for S0/A0, with a vertical side (-1 below, +1 above, 0 beside) chosen so that no two
    labels at the same end overprint: ``(x, y, label, side)``.

    >>> [a[2:] for a in _label_anchors([0, 1], {"S1": [2.9, 3], "S2": [3.1, 3.2]}, 8.0)]
    [('S1', -1), ('S2', 1)]
    """
    anchors = []
    for label, y in omega.items():
        y = _a(y)
        ok = np.flatnonzero(np.isfinite(y) & (y <= ymax))
        if ok.size:
            i = ok[-1] if label[1:] == "0" else ok[0]
            anchors.append((float(x[i]), float(y[i]), label))
    anchors.sort(key=lambda a: (a[0], a[1]))
    groups: list[list] = []
    for a in anchors:
        last = groups[-1][-1] if groups else None
        if last and last[0] == a[0] and a[1] - last[1] < LABEL_GAP * ymax:
            groups[-1].append(a)
        else:
            groups.append([a])
    out = []
    for group in groups:
        if len(group) == 1:
            xi, yi, lab = group[0]
            out.append((xi, yi, lab, 1 if lab[0] == "S" else -1))
            continue
        for j, (xi, yi, lab) in enumerate(group):
            out.append((xi, yi, lab, -1 if j == 0 else 1 if j == len(group) - 1 else 0))
    return out


def _label_modes(ax, x, omega: Mapping, ymax, color="k"):
    right = {}
    for xi, yi, label, side in _label_anchors(x, omega, ymax):
        fundamental = label[1:] == "0"
        dx = -3 if fundamental else 3
        if side == 0:  # the middle of a group: moved along its (flat) curve
            right[xi] = right.get(xi, 0) + 1
            dx += (-14 if fundamental else 14) * right[xi]
        ax.annotate(label, (xi, yi), xytext=(dx, 5 * side), textcoords="offset points",
                    fontsize="x-small", color=color, va="center",
                    ha="right" if fundamental else "left", clip_on=True)


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
        first = False
    _label_modes(ax, kappa, omega, omega_max)
    ax.set_xlabel(r"$\kappa = kh$")
    ax.set_ylabel(r"$\Omega = \omega h / c_T$")
    ax.set_ylim(0, omega_max)
    if kappa.size > 1:
        ax.set_xlim(float(np.nanmin(kappa)), float(np.nanmax(kappa)))  # the grid asked for
    return ax.figure


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
    return ax.figure


def plot_zone_edge(edge: float, ax=None):
    """Vertical line at the Brillouin-zone edge pi/r, explained in the legend (no text over
    the data); not drawn when the kappa axis ends before it."""
    ax = _axes(ax)
    lo, hi = ax.get_xlim()
    if lo <= edge <= hi:
        ax.axvline(edge, color="0.5", lw=0.9, ls=":",
                   label=f"zone edge $\\pi/r$ = {edge:.3g}: folded Bloch branches beyond it")
    return ax.figure


def _symlog(ax, linthresh: float, what: str):
    ax.axhline(0.0, color="0.4", lw=0.7)
    ax.set_yscale("symlog", linthresh=linthresh)
    ax.set_ylabel(f"{what} (signed; symlog, linear below {linthresh:.0e})")


def _broken(x: np.ndarray, y: np.ndarray, partner) -> tuple[np.ndarray, np.ndarray]:
    """``x, y`` with a NaN put between two points whose partners differ, so the line breaks
    where the pairing changes (a jump of the error is no vertical line of data).

    >>> _broken(np.array([1., 2, 3]), np.array([1., 1, 5]), [0, 0, 1])[1].tolist()
    [1.0, 1.0, nan, 5.0]
    """
    if partner is None:
        return x, y
    c = np.asarray(partner)
    cut = np.flatnonzero(c[1:] != c[:-1]) + 1
    return np.insert(x, cut, np.nan), np.insert(y, cut, np.nan)


def plot_paired_errors(kappa, errors: Mapping, ax=None, name: str = "", color: str = "C0",
                       branches: Sequence[str] = ("S0", "A0", "S1", "A1"),
                       linthresh: float = 1e-8, partners: Mapping | None = None):
    """Signed relative error of each exact branch against its shape partner, symlog axis;
    with ``partners`` (label -> the partner's place at each kappa) the line breaks where
    the partner changes."""
    ax = _axes(ax)
    kappa = _a(kappa)
    for b in branches:
        if b not in errors:
            continue
        e = _a(errors[b])
        e[np.abs(e) < ROUND_OFF] = np.nan  # round-off, not data
        if np.any(np.isfinite(e) & (kappa > 0)):
            x, y = _broken(kappa, e, (partners or {}).get(b))
            ax.plot(x, y, _BRANCH_STYLE.get(b, "-"), color=color, lw=1.2,
                    label=f"{name} {b}".strip())
    ax.set_xscale("log")
    ax.set_xlabel(r"$\kappa = kh$")
    _symlog(ax, linthresh, r"$(\Omega^h - \Omega)/\Omega$")
    return ax.figure


def _error_legend(ax, masses: Sequence[str]) -> None:
    """The error panel's key beside its axes, never over the curves: one entry per mass rule
    (its colour) and one per branch (its line style), instead of one per rule and branch."""
    from matplotlib.lines import Line2D

    drawn = {ln.get_label() for ln in ax.get_lines()}
    branches = [b for b in _BRANCH_STYLE if any(lab.endswith(f" {b}") for lab in drawn)]
    if not branches:
        return
    handles = [Line2D([], [], color=_colour(m), lw=2) for m in masses]
    handles += [Line2D([], [], color="0.3", ls=_BRANCH_STYLE[b], lw=1.2) for b in branches]
    ax.legend(handles, [*masses, *branches], fontsize="x-small", loc="center left",
              bbox_to_anchor=(1.01, 0.5), frameon=False)


def caption(inputs: Mapping) -> str:
    """A figure title from the recorded inputs of a branches run (the ``#`` lines of its CSV).

    >>> caption({"nu": 0.3, "model": "bloch", "r": 0.5, "p": 2, "n": 3,
    ...          "masses": ["consistent", "singular"], "contact": "top", "gamma_s": 0.0})
    'Rayleigh-Lamb, nu = 0.3; patch: bloch r = b/h = 0.5, p = 2, n = 3; consistent and singular mass (contact top, gamma_s = 0)'
    """
    head = f"Rayleigh-Lamb, nu = {inputs['nu']:g}"
    masses = list(inputs.get("masses") or ())
    if "material" in inputs:
        head += f" ({inputs.get('material', {}).get('name', 'material')})"
    if not masses:
        return head
    model = inputs["model"] + (f" r = b/h = {inputs['r']:g}" if "r" in inputs else "")
    singular = (f" (contact {inputs['contact']}, gamma_s = {inputs['gamma_s']:g})"
                if "contact" in inputs else "")
    return (f"{head}; patch: {model}, p = {inputs['p']}, n = {inputs['n']}; "
            f"{' and '.join(masses)} mass{singular}")


def figure2(data: Mapping, title: str = ""):
    """Figure 2 (right) of the paper plus the signed, shape-paired error panel.

    ``data``: :func:`dispersion.studies.branch_study.figure2_data` (or the stored JSON of it).
    """
    fig = new_figure(figsize=(12, 5.2))
    ax, ax_err = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.25, 1]})
    kappa = data["kappa"]
    plot_exact(kappa, {k: v["omega"] for k, v in data["exact"].items()}, data["omega_max"], ax)
    for i, (name, d) in enumerate(data["discrete"].items()):
        plot_discrete(kappa, d["omega"], d["symmetry"], ax, name, _colour(name, i), _marker(name))
        plot_paired_errors(kappa, d["paired_error"], ax_err, name, _colour(name, i),
                           partners=d.get("paired_partner"))
    edges = {d["zone_edge"] for d in data["discrete"].values() if d["zone_edge"] is not None}
    for edge in edges:
        plot_zone_edge(edge, ax)
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=3,
               fontsize="small")
    _error_legend(ax_err, list(data["discrete"]))
    ax_err.set_title("error of each exact branch against the discrete mode of the same shape\n"
                     "(MAC >= 0.5; no curve: no discrete mode resembles it; a gap: the partner "
                     "changes)", fontsize="small")
    if title:
        fig.suptitle(title, fontsize="medium")
    return fig


def figure_branch_table(table):
    """The figure of a :class:`~dispersion.answers.branch_table.BranchTable`, titled from it.

    With a material: phase and group velocity against fd and wavenumber against f in units,
    ZGV points and cut-offs marked, every discrete branch set as markers in its mass rule's
    style (first Brillouin zone). Without: the branches against kappa (Figure 2), each
    discrete set in its rule's style, and the panel of shape-paired errors when the table
    holds them (``branch_table(..., paired=True)``).
    """
    import numpy as np

    if table.material is not None:
        from dispersion.plotting.lamb import figure_dispersion
        from dispersion.answers.units import zgv_in_units

        discrete = {}
        for d, pb in zip(table.discrete, table.physical_discrete().values()):
            edge = d.branches.zone_edge
            inside = table.kappa <= (edge if edge is not None else np.inf)
            curves = {lab: {k: np.where(inside, v, np.nan) for k, v in c.items()}
                      for lab, c in pb.curves().items()}
            discrete[d.words()] = (d.patch.mass, curves)
        return figure_dispersion(table.physical().curves(), table.title(),
                                 zgv_in_units(table.zgv, table.material, table.thickness_mm),
                                 table.cutoffs_khz(), discrete=discrete)
    paired = any(d.paired_error is not None for d in table.discrete)
    fig = new_figure(figsize=(12, 5.2) if paired else (7.5, 5.6))
    if paired:
        ax, ax_err = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.25, 1]})
    else:
        ax, ax_err = fig.add_subplot(), None
    plot_exact(table.kappa, table.exact.omega, table.omega_max, ax)
    for d in table.discrete:
        colour, marker = _colour(d.patch.mass_name), _marker(d.patch.mass_name)
        plot_discrete(table.kappa, d.branches.omega, d.branches.symmetry, ax, d.words(),
                      colour, marker)
        if d.paired_error is not None:
            plot_paired_errors(table.kappa, d.paired_error, ax_err, d.patch.mass_name, colour,
                               partners=d.paired_partner)
    for edge in {d.branches.zone_edge for d in table.discrete} - {None}:
        plot_zone_edge(edge, ax)
    if table.discrete:
        fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=2,
                   fontsize="small")
    else:
        ax.legend(fontsize="small")
    if ax_err is not None:
        _error_legend(ax_err, [d.patch.mass_name for d in table.discrete
                               if d.paired_error is not None])
        ax_err.set_title("error of each exact branch against the discrete mode of the same "
                         "shape\n(MAC >= 0.5; no curve: no discrete mode resembles it; a gap: "
                         "the partner changes)", fontsize="small")
    import re
    import textwrap

    # an interval "[0, 8]" is never split over two lines (a no-break space inside it)
    title = re.sub(r"\[([^\]]*?), ", "[\\1,\u00a0", table.title())
    fig.suptitle(textwrap.fill(title, 110), fontsize="medium")
    return fig


def figure_velocities(data: Mapping, discrete: str = "consistent", fd_per_omega=None,
                      zgv: Sequence[Mapping] = ()):
    """Phase and group velocity (over c_T) against Omega: exact lines, discrete markers, ZGV."""
    fig = new_figure(figsize=(12, 4.6))
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


_DEGREE_MARKERS = {1: "x", 2: "o", 3: "s", 4: "^"}


def _plot_signed_log(ax, x, e, color, marker, label, offset=0, zorder=2):
    """|e| on a log axis, solid where e > 0 and dashed where e < 0; a sign change leaves a
    gap (no vertical line), values below ``ROUND_OFF`` are round-off and not drawn."""
    x, e = _a(x), _a(e)
    a = np.abs(e)
    a[~(a >= ROUND_OFF)] = np.nan
    every = (offset % 9, 9)
    ax.plot(x, np.where(e > 0, a, np.nan), "-", color=color, marker=marker, ms=3.5,
            markevery=every, mfc="none", lw=1.2, label=label, zorder=zorder)
    ax.plot(x, np.where(e < 0, a, np.nan), "--", color=color, marker=marker, ms=3.5,
            markevery=every, mfc="none", lw=1.2, zorder=zorder)


#: Drawing order of the masses: the lumped curves first, so that a singular curve close to
#: them stays visible on top.
_MASS_ORDER = {"lumped": 0, "consistent": 1, "singular-lumped": 2, "singular": 3}


def _spec(stored: Mapping | None):
    """The :class:`~dispersion.symbolic.patch.Patch` a result stored (None in older records)."""
    if not stored:
        return None
    from dispersion.symbolic.patch import Patch

    return Patch.from_dict(stored)


def _curve_label(c: Mapping) -> str:
    """Legend entry of a per-wavelength curve: its degree and size, and its mass with the
    contact set and gamma_s where they apply (from the stored patch when there is one)."""
    spec = _spec(c.get("patch"))
    mass = spec.mass_title() if spec is not None else c["mass"]
    return f"p = {c['p']} (n = {c['n']}), {mass}"


def _plate_geometry(curves: Sequence[Mapping], r) -> str:
    """The model and aspect ratio the curves share, from their stored patches."""
    specs = [_spec(c.get("patch")) for c in curves]
    if specs and all(specs):
        names = dict.fromkeys(f"Bloch patch r = b/h = {sp.r}" if sp.model == "bloch"
                              else f"{sp.model} patch" for sp in specs)
        return " / ".join(names)
    return f"Bloch patch r = b/h = {r:g}"  # an older record: its stored r


def figure_per_wavelength(per_wavelength: Mapping, bar: Mapping, nu: float | None = None):
    """|Relative phase-velocity error| against elements per wavelength on log-log axes, its
    sign by line style: plate S0, A0 and the 1D bar. Colour: mass; marker: degree p."""
    fig = new_figure(figsize=(13, 6.4))
    axs = fig.subplots(1, 3, sharey=True)
    epw = per_wavelength["elements_per_wavelength"]
    curves = sorted(per_wavelength["curves"], key=lambda c: _MASS_ORDER.get(c["mass"], 9))
    for ax, branch in zip(axs[:2], ("S0", "A0")):
        for c in curves:
            if c["branch"] == branch:
                _plot_signed_log(ax, epw, c["error"], _colour(c["mass"]),
                                 _DEGREE_MARKERS.get(c["p"], "d"),
                                 _curve_label(c),
                                 offset=3 * _MASS_ORDER.get(c["mass"], 0) + c["p"],
                                 zorder=2 + _MASS_ORDER.get(c["mass"], 0))
        ax.set_title(f"plate {branch}, {_plate_geometry(curves, per_wavelength['r'])}",
                     fontsize="small")
    keys = sorted(bar["error"], key=lambda k: _MASS_ORDER.get(k.split()[1], 9))
    for key in keys:
        p, mass = int(key.split()[0][2:]), key.split()[1]
        _plot_signed_log(axs[2], bar["elements_per_wavelength"], bar["error"][key],
                         _colour(mass), _DEGREE_MARKERS.get(p, "d"), f"p = {p}, {mass}",
                         offset=p)
    axs[2].set_title("1D bar, periodic B-splines (Cottrell et al. 2006)", fontsize="small")
    keys = {}
    for ax in axs:
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("elements per wavelength")
        ax.grid(True, which="major", alpha=0.3)
        for h, lab in zip(*ax.get_legend_handles_labels()):
            keys.setdefault(lab, h)
    if keys:  # one key below the panels, never over them: the curves separate where it sat
        from matplotlib.lines import Line2D

        keys[r"solid: $\Omega^h > \Omega$ (too fast)"] = Line2D([], [], color="0.3", ls="-")
        keys[r"dashed: $\Omega^h < \Omega$ (too slow)"] = Line2D([], [], color="0.3", ls="--")
        fig.legend(list(keys.values()), list(keys), loc="outside lower center", ncol=4,
                   fontsize="x-small")
    axs[0].set_ylabel(r"$|c_p^h / c_p - 1| = |\Omega^h/\Omega - 1|$ (below 1e-13: round-off, "
                      "not drawn)")
    if nu is not None:
        fig.suptitle(f"Discretization error per wavelength, nu = {nu:g}", fontsize="medium")
    return fig


def figure_shapes(shapes: Mapping):
    """Exact (lines) and discrete (markers) through-thickness mode shapes with their MAC."""
    modes = shapes["modes"]
    fig = new_figure(figsize=(3.0 * len(modes), 3.6))
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
    spec = _spec(shapes.get("patch"))
    patch = (f"the patch {spec.title()}" if spec is not None
             else "the discrete patch (not recorded in this older result)")
    fig.suptitle(f"mode shapes at $\\kappa$ = {shapes['kappa']:g}: exact (lines) and {patch} "
                 "(markers; its Omega in brackets)", fontsize="small")
    return fig


def plot_speed_accuracy(rows: Sequence[Mapping], ax=None, label=None, floor: float | None = None,
                        order=None, point_label=None):
    """Error against wall time, one line per group of ``rows`` (``label(row)`` names it),
    points joined in the order of ``order(row)`` (default: time).

    Errors below ``floor`` (the reference's own accuracy) carry no information: they are
    drawn at the floor as open markers (and the legend says so only if there are any).
    ``point_label(row)`` writes a label beside each point (e.g. its rtol).
    """
    ax = _axes(ax)
    label = label or (lambda r: str(r.get("name", "")))
    groups: dict[str, list] = {}
    for row in rows:
        groups.setdefault(label(row), []).append(row)
    any_below = False
    point_labels = []
    for i, (name, rs) in enumerate(groups.items()):
        rs = sorted(rs, key=order or (lambda r: r["time_s"]))
        t = np.array([r["time_s"] for r in rs])
        e = np.array([np.nan if r["error"] is None else r["error"] for r in rs])
        lo = floor if floor else 0.0
        below = e <= lo
        ax.loglog(t, np.where(below, lo, e), "-", color=f"C{i}", label=name)
        ax.loglog(t[~below], e[~below], "o", color=f"C{i}")
        if below.any():
            any_below = True
            ax.loglog(t[below], np.full(below.sum(), lo), "o", color=f"C{i}", mfc="none")
        if point_label is not None:
            point_labels += [(ti, ei, point_label(row), f"C{i}")
                             for ti, ei, row in zip(t, np.where(below, lo, e), rs)]
    if floor:
        ax.axhline(floor, color="0.4", lw=0.8, ls=":",
                   label="reference's own error" + (" (open markers: at or below it)"
                                                    if any_below else ""))
    _time_ticks(ax)
    if point_labels:
        from dispersion.plotting.labels import place_labels

        ax.autoscale_view()
        place_labels(ax, point_labels, fontsize=6)  # apart: no label over another
    ax.set_xlabel("wall time [s]")
    ax.legend(fontsize="x-small")
    return ax.figure


def _time_ticks(ax) -> None:
    """Labelled ticks on a logarithmic time axis however short its range: 1, 2 and 5 times
    the decades inside it, or, if fewer than two of those fall inside (a range within one
    decade had no labelled tick at all), four evenly spaced round values; written short
    (``0.045``), never in scientific notation that runs into its neighbour."""
    import math

    from matplotlib.ticker import FixedLocator, FuncFormatter, MaxNLocator, NullFormatter

    ax.autoscale_view()
    lo, hi = ax.get_xlim()
    if not (lo > 0 and hi > lo):
        return
    ticks = [m * 10.0**k for k in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1)
             for m in (1, 2, 5) if lo <= m * 10.0**k <= hi]
    if len(ticks) < 2:
        ticks = [t for t in MaxNLocator(nbins=4).tick_values(lo, hi) if lo <= t <= hi]
    if len(ticks) > 8:  # many decades: the decades alone
        ticks = [t for t in ticks if math.isclose(10 ** round(math.log10(t)), t)]
    ax.xaxis.set_major_locator(FixedLocator(ticks))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.3g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())


def figure_speed_accuracy(tracer: Mapping, discrete_rows: Sequence[Mapping]):
    """Tracer (per scan step) and discrete solver (per p and mass) speed/accuracy panels."""
    fig = new_figure(figsize=(11, 4.2))
    a1, a2 = fig.subplots(1, 2)
    ref = tracer["reference"]
    plot_speed_accuracy(tracer["rows"], a1, label=lambda r: "exact tracer",
                        floor=tracer["reference_mpmath_error"], order=lambda r: -r["rtol"],
                        point_label=lambda r: f"{r['rtol']:.0e}")
    a1.set_title(f"Rayleigh-Lamb tracer, {tracer['kappa_count']} kappa, Omega <= "
                 f"{tracer['omega_max']:g}; points: rtol\nerror vs reference (rtol {ref[1]:g}; "
                 f"rtol falls along the line), itself vs 40-digit mpmath: "
                 f"{tracer['reference_mpmath_error']:.1e}", fontsize="small")
    a1.set_ylabel("max relative error of the roots")
    plot_speed_accuracy(discrete_rows, a2, label=lambda r: f"p = {r['p']}, {r['mass']}",
                        order=lambda r: r["n"], point_label=lambda r: f"n={r['n']}")
    a2.set_title("discrete branches (points: n = p+1, p+3 control points)",
                 fontsize="small")
    a2.set_ylabel("max |relative error| S0/A0, kappa <= 1")
    return fig
