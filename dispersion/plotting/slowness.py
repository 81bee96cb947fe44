"""Slowness curves of a layered plate: the slowness 1/c_p of every mode against the direction
of the waves, in polar form (:class:`~dispersion.answers.slowness_table.SlownessTable`).

Drawn from plain data: ``points`` maps a family (S, A, SH, L, M) to arrays ``angle``
(degrees), ``slowness`` (s/km) and ``mode`` (:meth:`SlownessTable.points`). Each root is a
point, not a line: a mode's name changes with its family from one direction to the next (SH0
of a cross-ply along its plies becomes S1 between them), so joining points by name would
draw lines that are not curves. S blue, A red, SH green, L and M black.

>>> import numpy as np
>>> p = {"S": {"angle": np.array([0.0, 45.0]), "slowness": np.array([0.14, 0.2]),
...            "mode": np.array(["S0", "S0"])}}
>>> fig = figure_slowness_points(p, "a plate")
>>> fig.axes[0].name
'polar'
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from dispersion.plotting import new_figure

__all__ = ["figure_slowness", "figure_slowness_points", "plot_slowness"]

_COLOUR = {"S": "C0", "A": "C3", "SH": "C2", "L": "k", "M": "k"}
_MARKER = {"S": "o", "A": "s", "SH": "^", "L": "o", "M": "o"}


def plot_slowness(points: Mapping, ax) -> None:
    """The points of every family on the polar Axes ``ax`` (angle in degrees, radius the
    slowness in s/km)."""
    for fam, d in points.items():
        ax.plot(np.radians(d["angle"]), d["slowness"], linestyle="none",
                marker=_MARKER.get(fam, "o"), markersize=3, color=_COLOUR.get(fam, "k"),
                label=f"{fam} modes")
    ax.set_xlabel("direction of the waves from the plate's 0 deg axis")
    ax.set_ylabel("slowness 1/c_p [s/km]", labelpad=28)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="small")


def figure_slowness_points(points: Mapping, title: str):
    """A polar figure of ``points`` titled ``title``."""
    fig = new_figure(figsize=(7.0, 5.5))
    ax = fig.add_subplot(projection="polar")
    plot_slowness(points, ax)
    ax.set_title(title, fontsize="medium")
    return fig


def figure_slowness(table):
    """The figure of a :class:`~dispersion.answers.slowness_table.SlownessTable`, titled from
    it."""
    return figure_slowness_points(table.points(), table.title())
