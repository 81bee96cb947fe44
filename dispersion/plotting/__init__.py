"""Plot functions (matplotlib, the ``plots`` extra). Each returns the Figure it drew on.

``plot_*`` functions take ``ax=None`` (draw into that Axes, or into a new figure) and
``figure_*`` functions lay out several panels; both return a pyplot-free
:class:`matplotlib.figure.Figure` that shows itself as an image in Jupyter (``_repr_png_``),
so a notebook cell that ends in a plot call displays the plot. Numerics never import this
package; it imports matplotlib lazily, and :func:`require_matplotlib` says which extra to
install before any work starts.

>>> fig = new_figure(figsize=(2, 1))
>>> type(fig).__name__, fig._repr_png_()[:4]
('Figure', b'\\x89PNG')
"""
from __future__ import annotations

import functools

__all__ = ["PLOTS_EXTRA", "axes", "new_figure", "require_matplotlib"]

#: What to install for figures.
PLOTS_EXTRA = 'pip install "dispersion-iga[plots]"'


@functools.cache
def _figure_class():
    from matplotlib.figure import Figure as _Base

    class Figure(_Base):
        """A pyplot-free Figure that displays itself in Jupyter as a PNG."""

        def _repr_png_(self) -> bytes:
            import io

            buf = io.BytesIO()
            self.savefig(buf, format="png", dpi=100)
            return buf.getvalue()

    Figure.__module__ = __name__
    Figure.__qualname__ = "Figure"
    return Figure


def new_figure(**kwargs):
    """A new pyplot-free Figure (``layout="constrained"`` unless given) that displays in Jupyter."""
    kwargs.setdefault("layout", "constrained")
    return _figure_class()(**kwargs)


def axes(ax=None, size=(5.5, 4.0)):
    """``ax`` itself, or the Axes of a new figure of ``size`` inches (:func:`new_figure`)."""
    if ax is None:
        ax = new_figure(figsize=size).add_subplot()
    return ax


def require_matplotlib(what: str) -> None:
    """Raise :class:`~dispersion.errors.InputError` naming the ``plots`` extra if matplotlib
    cannot be imported; called before any work, so a missing extra costs no computation.

    >>> require_matplotlib("a figure")  # matplotlib is installed for the tests
    """
    from dispersion.errors import InputError

    try:
        import matplotlib  # noqa: F401
        import matplotlib.figure  # noqa: F401
    except ImportError:
        raise InputError(f"{what} needs matplotlib, which is not installed: {PLOTS_EXTRA} "
                         '(from a checkout: pip install -e ".[plots]")') from None
