"""Text labels beside points that never overprint one another.

:func:`place_labels` writes each label next to its point, then moves labels apart vertically
(in points, as the text is measured) wherever two of them would share a place: labels whose
points lie within a label's width of each other along x are stacked one line apart, in the
order of their points, and kept inside the axes. The points themselves never move.

>>> from dispersion.plotting import new_figure
>>> ax = new_figure().add_subplot()
>>> _ = ax.plot([0, 1], [0, 1])
>>> texts = place_labels(ax, [(1.0, 0.5, "S0", "C0"), (1.0, 0.5, "S1", "C0")])
>>> [t.get_text() for t in texts], len({t.xyann[1] for t in texts})    # two heights
(['S0', 'S1'], 2)
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

__all__ = ["place_labels", "label_offsets"]


def label_offsets(fx: Sequence[float], fy: Sequence[float], gap: float, width: float
                  ) -> np.ndarray:
    """Vertical offsets (in the units of ``fy``) that put labels anchored at ``(fx, fy)`` (axes
    fractions) at least ``gap`` apart wherever their anchors lie within ``width`` along x,
    the stack centred on its anchors and kept inside [0, 1] where it fits.

    >>> label_offsets([0.9, 0.9, 0.2], [0.5, 0.5, 0.5], 0.1, 0.05).round(3).tolist()
    [-0.05, 0.05, 0.0]
    """
    fx, fy = np.asarray(fx, float), np.asarray(fy, float)
    out = np.zeros(fx.size)
    order = np.argsort(fx, kind="stable")
    clusters, current = [], []
    for i in order:  # neighbours along x within a label's width: one stack
        if current and fx[i] - fx[current[-1]] > width:
            clusters.append(current)
            current = []
        current.append(i)
    if current:
        clusters.append(current)
    for members in clusters:
        members = sorted(members, key=lambda i: (fy[i], i))
        y = fy[members].copy()
        for k in range(1, len(y)):  # each at least a gap above the one below
            y[k] = max(y[k], y[k - 1] + gap)
        y -= (y - fy[members]).mean()  # the stack centred on its anchors
        y -= max(0.0, y[-1] - 1.0)         # kept inside the axes: top, then bottom
        y += max(0.0, -y[0])
        out[members] = y - fy[members]
    return out


def place_labels(ax, items, fontsize: float = 7.0, dx: float = 2.0):
    """Annotate ``items`` ``(x, y, text, colour)`` (data coordinates) on ``ax`` without
    overprinting (module docstring); returns the Annotations."""
    items = [it for it in items if np.isfinite(it[0]) and np.isfinite(it[1])]
    if not items:
        return []
    fig = ax.figure
    pos = ax.get_position()
    height = max(pos.height * fig.get_figheight() * 72.0, 1.0)  # points
    width = max(pos.width * fig.get_figwidth() * 72.0, 1.0)
    frac = ax.transAxes.inverted().transform(ax.transData.transform(
        np.array([[x, y] for x, y, _, _ in items], dtype=float)))
    longest = max(len(str(t)) for _, _, t, _ in items)
    shift = label_offsets(frac[:, 0], frac[:, 1], gap=(fontsize + 1.5) / height,
                          width=(0.7 * fontsize * longest + dx) / width)
    return [ax.annotate(text, (x, y), xytext=(dx, 2.0 + s * height), textcoords="offset points",
                        fontsize=fontsize, color=colour, va="bottom", annotation_clip=False)
            for (x, y, text, colour), s in zip(items, shift)]
