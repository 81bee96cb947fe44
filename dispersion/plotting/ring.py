"""Figures of the ring study and the impact scenes (:mod:`dispersion.contact`), from data.

Every function takes plain data as loaded from JSON (``{"summary": ..., "series": ...}``
runs, grid rows) and ``ax=None``, and returns the Figure; :func:`figure4` lays out the paper's
Figure 4 on a pyplot-free Figure.

>>> run = {"summary": {"mass": "lumped", "scheme": "kane", "energy_change_percent": -5.0},
...        "series": {"t": [0, 1, 2], "contact_force": [0, 1, 0], "total": [1, 1, 0.95]}}
>>> plot_contact_energy(run).axes[0].get_xlabel()
'time t (s)'
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from dispersion.plotting import axes, new_figure

__all__ = ["caption", "energy_change_percent", "figure4", "plot_contact_energy",
           "plot_energy_change", "plot_grid", "plot_signorini", "plot_impact"]


def _axes(ax, size=(6.0, 3.2)):
    return axes(ax, size)


def _arr(run, key):
    return np.asarray(run["series"][key], dtype=float)


def energy_change_percent(run: dict) -> np.ndarray:
    """Total energy against time as change relative to its initial value, in %."""
    total = _arr(run, "total")
    return 100 * (total - total[0]) / total[0]


def caption(run: dict) -> str:
    """Title of one ring run from its stored data: mass, scheme, scene (if stored), result."""
    s = run["summary"]
    text = (f"ring, {s['mass']} mass ({s['scheme']}): energy change "
            f"{s['energy_change_percent']:+.3f} %")
    sc = run.get("scenario")
    if sc:
        text += (f"\nr = {sc['r_inner']:g}-{sc['r_outer']:g} m, arc from {sc['theta0_deg']:g} "
                 f"deg, v0 = {sc['v0']:g} m/s, dt = {sc['dt']:g} s, t_end = {sc['t_end']:g} s")
    return text


def plot_contact_energy(run: dict, ax=None, title: str | None = None, force_max=None):
    """Contact force (left axis) and the change of total energy relative to its initial
    value in % (right axis) of one ring run: a few per cent are visible, not lost on a 0 to
    E0 axis."""
    ax = _axes(ax)
    t = _arr(run, "t")
    ax.plot(t, _arr(run, "contact_force"), color="C0", lw=1.0, label="contact force")
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("contact force (N/m)", color="C0")
    if force_max is not None:
        ax.set_ylim(0, force_max)
    right = ax.twinx()
    right.plot(t, energy_change_percent(run), color="C3", lw=1.2, label="total energy change")
    right.axhline(0.0, color="C3", lw=0.6, ls=":")
    right.set_ylabel(r"total energy change $\Delta E / E_0$ (%)", color="C3")
    ax.set_title(title or caption(run), fontsize=9)
    return ax.figure


def plot_energy_change(runs: dict, paper: dict | None = None, ax=None):
    """:math:`\\Delta E / E_0` (%) against time, one line per mass, the paper's values dashed."""
    ax = _axes(ax)
    for k, (mass, run) in enumerate(runs.items()):
        total = _arr(run, "total")
        ax.plot(_arr(run, "t"), 100 * (total - total[0]) / total[0], color=f"C{k}", lw=1.2,
                label=mass)
        if paper and mass in paper:
            ax.axhline(paper[mass], color=f"C{k}", ls="--", lw=0.8,
                       label=f"paper, {mass}: {paper[mass]:g} %")
    ax.set_xlabel("time t (s)")
    ax.set_ylabel(r"$\Delta E / E_0$ (%)")
    ax.legend(fontsize=7)
    return ax.figure


def _first_impact(run: dict, pad: float = 0.5):
    t, F = _arr(run, "t"), _arr(run, "contact_force")
    on = np.flatnonzero(F > 1e-9 * max(F.max(), 1e-300))
    if not len(on):
        return t[0], t[-1]
    # the first contact interval: until the force has been zero for a while
    gaps = np.flatnonzero(np.diff(on) > 5)
    end = on[gaps[0]] if len(gaps) else on[-1]
    span = t[end] - t[on[0]]
    return t[on[0]] - pad * span, t[end] + pad * span


def scene_caption(sc: dict) -> str:
    """One line naming a ring scene from its stored fields."""
    return (f"quarter ring r = {sc['r_inner']:g}-{sc['r_outer']:g} m, arc from "
            f"{sc['theta0_deg']:g} deg, gap {sc['gap']:g} m, v0 = {sc['v0']:g} m/s, "
            f"E = {sc['E']:.4g} Pa, nu = {sc['nu']:g}, rho = {sc['rho']:g} kg/m^3, "
            f"{sc['n_xi_elements']} x {sc['n_eta_elements']} elements, dt = {sc['dt']:g} s")


def figure4(lumped: dict, singular: dict, paper: dict | None = None,
            scenario: dict | None = None):
    """Paper Figure 4 with one force axis for both masses, plus Delta E / E0 and a zoom on the
    first impact; titled with the scene (``scenario``, or the runs' own if they carry it)."""
    fig = new_figure(figsize=(10, 7.8))
    sc = scenario or lumped.get("scenario")
    if sc:
        import textwrap

        from dispersion.contact.newmark_scheme import SCHEME_TEXT

        name = lumped["summary"]["scheme"]
        fig.suptitle(textwrap.fill(f"Figure 4: {SCHEME_TEXT.get(name, name)}, "
                                   + scene_caption(sc), 110), fontsize="small")
    grid = fig.subplot_mosaic([["l", "lz"], ["s", "sz"], ["e", "e"]],
                              gridspec_kw={"width_ratios": (2.2, 1)})
    fmax = 1.08 * max(np.max(_arr(r, "contact_force")) for r in (lumped, singular))
    for key, run in (("l", lumped), ("s", singular)):
        plot_contact_energy(run, grid[key], force_max=fmax)
        lo, hi = _first_impact(run)
        ax = grid[key + "z"]
        t = _arr(run, "t")
        sel = (t >= lo) & (t <= hi)
        ax.plot(t[sel], _arr(run, "contact_force")[sel], "o-", ms=2, lw=0.8, color="C0")
        ax.set_ylim(0, fmax)
        ax.set_xlabel("time t (s)")
        ax.set_ylabel("contact force (N/m)")
        ax.set_title(f"{run['summary']['mass']}: first impact (dots: steps)", fontsize=9)
    plot_energy_change({"lumped": lumped, "singular": singular}, paper, grid["e"])
    grid["e"].set_title("energy change against time", fontsize=9)
    return fig


def plot_grid(rows: Sequence[dict], paper: dict | None = None, ax=None,
              default_steps: float | None = None):
    """|Energy change| (%) against steps per impact, one line per (mass, landing angle);
    the paper's values dashed, the default scene's steps per impact dotted."""
    from matplotlib.ticker import ScalarFormatter

    ax = _axes(ax, (8.0, 3.8))
    masses = sorted({r["mass"] for r in rows})
    angles = sorted({r["theta0_deg"] for r in rows})
    markers = "osd^v"
    for k, mass in enumerate(masses):
        for j, ang in enumerate(angles):
            sel = sorted((r for r in rows if r["mass"] == mass and r["theta0_deg"] == ang
                          and r.get("converged")), key=lambda r: r["steps_per_impact"])
            ax.plot([r["steps_per_impact"] for r in sel],
                    [abs(r["energy_change_percent"]) for r in sel], marker=markers[j % 5],
                    color=f"C{k}", lw=1, label=f"{mass}, arc from {ang:g} deg")
        if paper and mass in paper:
            ax.axhline(abs(paper[mass]), color=f"C{k}", ls="--", lw=0.8,
                       label=f"paper, {mass}: {paper[mass]:g} %")
    if default_steps is not None:
        ax.axvline(default_steps, color="0.4", ls=":", lw=1, label="default scene")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(ScalarFormatter())
    ax.set_xlabel("steps per impact (2 t / (c_p dt))")
    ax.set_ylabel("|energy change| (%)")
    ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    return ax.figure


def plot_signorini(history: dict, exact: dict, ax=None, title: str | None = None):
    """Contact stress at x = 0 against time: computed (``history``) and exact."""
    ax = _axes(ax)
    ax.plot(exact["t"], exact["stress"], "k-", lw=1.5, label="exact")
    ax.plot(history["t"], history["stress"], color="C0", lw=0.8, label="computed")
    ax.set_xlabel("time t (dimensionless)")
    ax.set_ylabel(r"contact stress $-u_x(0, t)$")
    ax.legend(fontsize=8)
    if title:
        ax.set_title(title, fontsize=9)
    return ax.figure


def plot_impact(result, ax=None):
    """Contact stress of a :class:`dispersion.contact.signorini.SignoriniResult` against the
    exact solution, titled with the run's inputs and its stress error."""
    from dispersion.contact.signorini import exact_solution

    ex = exact_solution(float(result.t[-1]))
    err = result.errors["stress_rel_l2"]  # None: the exact stress is 0 throughout the run
    title = (f"{result.title()}\nrelative L2 error of the contact stress "
             + ("n/a (exact stress 0 throughout)" if err is None else f"{err:.3g}"))
    return plot_signorini({"t": result.t, "stress": result.stress},
                          {"t": result.t, "stress": ex.stress(result.t)}, ax, title=title)
