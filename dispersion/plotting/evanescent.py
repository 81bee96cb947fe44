"""The evanescent modes of a plate against frequency, as Mindlin drew the complex spectrum of
the Rayleigh-Lamb equations (:class:`~dispersion.answers.evanescent_mode_table.
EvanescentModeTable`): the decay Im k to the left of the frequency axis, the wavenumber
Re k of the complex roots to the right.

Drawn from the table's rows (``rows``: dicts with ``f [kHz]``, ``family``, ``kind``,
``Re k [rad/mm]``, ``Im k [1/mm]``): each root is a point, not a line, because the names are
ranks by Im k at each frequency, not branches followed through frequency. An imaginary root
(Re k = 0) is a filled marker in the left panel only; a complex root an open marker in both
panels, at the same height. S blue, A red, SH green, L and M black (the slowness figure's
colours).

>>> rows = [{"f [kHz]": 100.0, "family": "A", "kind": "imaginary", "Re k [rad/mm]": 0.0,
...          "Im k [1/mm]": 0.5},
...         {"f [kHz]": 100.0, "family": "S", "kind": "complex", "Re k [rad/mm]": 2.3,
...          "Im k [1/mm]": 4.1}]
>>> fig = figure_evanescent_rows(rows, "a plate", "f [kHz]")
>>> [ax.get_xlabel() for ax in fig.axes]
['Im k [1/mm] (decay)', 'Re k [rad/mm] (complex roots)']
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from dispersion.plotting import new_figure
from dispersion.plotting.slowness import _COLOUR, _MARKER   # one colour per family

__all__ = ["figure_evanescent", "figure_evanescent_rows"]


def figure_evanescent_rows(rows: Sequence, title: str, axis: str = "f [kHz]",
                           bound: tuple | None = None):
    """Two panels sharing the frequency axis ``axis`` (a key of each row): Im k (inverted,
    growing to the left) and Re k of the complex roots; titled ``title``; ``bound`` ``(Im k
    [1/mm], caption)``: the edge of the searched region, a dotted line."""
    fig = new_figure(figsize=(9.0, 6.0))
    left, right = fig.subplots(1, 2, sharey=True)
    families = list(dict.fromkeys(r["family"] for r in rows))
    for fam in families:
        for kind in ("imaginary", "complex"):
            mine = [r for r in rows if r["family"] == fam and r["kind"] == kind]
            if not mine:
                continue
            f = np.array([r[axis] for r in mine])
            style = {"linestyle": "none", "marker": _MARKER.get(fam, "o"), "markersize": 4,
                     "color": _COLOUR.get(fam, "k"), "label": f"{fam}, {kind}"}
            if kind == "complex":
                style["markerfacecolor"] = "none"
            left.plot([r["Im k [1/mm]"] for r in mine], f, **style)
            if kind == "complex":
                right.plot([r["Re k [rad/mm]"] for r in mine], f, **style)
    if bound is not None:
        left.axvline(bound[0], color="0.4", lw=0.8, ls=":", label=bound[1])
    left.set_xlim(left=0.0)
    left.invert_xaxis()
    right.set_xlim(left=0.0)
    left.set_xlabel("Im k [1/mm] (decay)")
    right.set_xlabel("Re k [rad/mm] (complex roots)")
    left.set_ylabel(axis)
    for ax in (left, right):
        ax.grid(True, color="0.9", lw=0.6)
    handles, labels = left.get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, fontsize="small", loc="outside lower center",
                   ncol=min(len(handles), 4), frameon=False)
    fig.suptitle(title, fontsize="medium")
    return fig


def figure_evanescent(table):
    """The figure of an :class:`~dispersion.answers.evanescent_mode_table.
    EvanescentModeTable`, titled from it (with its count of uncertified roots, if any)."""
    title = table.title()
    if table.roots.failures:
        title += f" ({len(table.roots.failures)} not certified, not drawn)"
    h_mm = table.plate.scaled().h_m * 1e3
    bound = (table.roots.im_max / h_mm, f"searched to {table.decay_db:g} dB per thickness")
    return figure_evanescent_rows(table.rows(), title, bound=bound)
