"""Plot functions (matplotlib). Each takes ``ax=None`` and returns the Axes it drew on.

Numerics never import this package; it imports matplotlib lazily.
"""


def axes(ax=None, size=(5.5, 4.0)):
    """``ax`` itself, or the Axes of a new pyplot-free Figure of ``size`` inches."""
    if ax is None:
        from matplotlib.figure import Figure

        ax = Figure(figsize=size, layout="constrained").add_subplot()
    return ax
