"""How a set of branches on a kappa grid shows itself: short reprs, HTML, a DataFrame.

:class:`BranchViews` is mixed into :class:`~dispersion.waves.discrete_branches.DiscreteBranches`
and :class:`~dispersion.waves.exact_branches.ExactBranches` (both hold ``kappa`` and
``omega[label]``). A repr names the grid and the branches, never whole arrays, so a notebook
cell or a log line stays short; ``to_dataframe()`` gives the long table (one row per kappa and
branch) when pandas is installed (the ``dataframe`` extra).

>>> import numpy as np
>>> from dispersion.waves.exact_branches import ExactBranches
>>> b = ExactBranches(np.linspace(0, 1, 3), {"S0": np.array([0.0, 0.8, 1.6]),
...                                          "A0": np.array([0.0, 0.3, np.nan])}, 0.3, 2.0)
>>> b
ExactBranches(nu=0.3, 3 kappa in [0, 1], Omega <= 2, branches S0, A0, 0 failures)
>>> b.to_dataframe().shape  # S0 on 3 points, A0 on 2
(5, 4)
"""
from __future__ import annotations

import math

import numpy as np

from dispersion.errors import InputError

__all__ = ["BranchViews", "DATAFRAME_EXTRA", "require_pandas"]

#: What to install for ``to_dataframe()``.
DATAFRAME_EXTRA = 'pip install "dispersion-iga[dataframe]"'


def require_pandas():
    """pandas, or :class:`InputError` naming the ``dataframe`` extra."""
    try:
        import pandas
    except ImportError:
        raise InputError(f"to_dataframe() needs pandas, which is not installed: "
                         f"{DATAFRAME_EXTRA}") from None
    return pandas


def _g(x) -> str:
    return "nan" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.4g}"


class BranchViews:
    """Short ``repr``, ``_repr_html_`` and ``to_dataframe`` of a branch set (see module)."""

    def _facts(self) -> list[str]:
        kappa = np.asarray(self.kappa, dtype=float)
        facts = []
        if getattr(self, "nu", None) is not None:
            facts.append(f"nu={_g(self.nu)}")
        span = (f" in [{_g(float(kappa.min()))}, {_g(float(kappa.max()))}]" if kappa.size
                else "")
        facts.append(f"{kappa.size} kappa{span}")
        if getattr(self, "omega_max", None) is not None:
            facts.append(f"Omega <= {_g(self.omega_max)}")
        labels = list(self.omega)
        shown = ", ".join(labels[:8]) + (f", ... ({len(labels)} in all)" if len(labels) > 8
                                         else "")
        facts.append(f"branches {shown or 'none'}")
        if getattr(self, "zone_edge", None) is not None:
            facts.append(f"zone edge pi/r = {_g(self.zone_edge)}")
        if hasattr(self, "group"):
            facts.append("group velocities" if self.group is not None else "no group velocities")
        if hasattr(self, "failures"):
            facts.append(f"{len(self.failures)} failures")
        return facts

    def __repr__(self) -> str:
        return f"{type(self).__name__}({', '.join(self._facts())})"

    def _symmetry_of(self, label: str) -> str:
        """The symmetry of branch ``label``: discrete sets store a dict, exact ones a rule."""
        if isinstance(self.symmetry, dict):
            return self.symmetry.get(label, "")
        return self.symmetry(label)

    def _repr_html_(self) -> str:
        import html

        rows = []
        for label, w in self.omega.items():
            w = np.asarray(w, dtype=float)
            ok = np.isfinite(w)
            sym = self._symmetry_of(label)
            lo, hi = (_g(float(w[ok].min())), _g(float(w[ok].max()))) if ok.any() else ("-", "-")
            rows.append(f"<tr><td>{html.escape(label)}</td><td>{html.escape(sym)}</td>"
                        f"<td>{int(ok.sum())}</td><td>{lo}</td><td>{hi}</td></tr>")
        return (f"<p><code>{html.escape(repr(self))}</code></p><table><thead><tr><th>branch</th>"
                "<th>symmetry</th><th>points</th><th>min Omega</th><th>max Omega</th></tr>"
                "</thead><tbody>" + "".join(rows) + "</tbody></table>")

    def to_dataframe(self):
        """One row per (kappa, branch) where the branch exists: ``kappa, branch, symmetry,
        Omega`` and, where computed, ``c_g/c_T`` (group velocity over the shear speed)."""
        pd = require_pandas()
        kappa = np.asarray(self.kappa, dtype=float)
        group = getattr(self, "group", None) or {}
        frames = []
        for label, w in self.omega.items():
            w = np.asarray(w, dtype=float)
            ok = np.isfinite(w)
            sym = self._symmetry_of(label)
            cols = {"kappa": kappa[ok], "branch": label, "symmetry": sym, "Omega": w[ok]}
            if group:
                g = np.asarray(group.get(label, np.full(kappa.shape, np.nan)), dtype=float)
                cols["c_g/c_T"] = g[ok]
            frames.append(pd.DataFrame(cols))
        if not frames:
            return pd.DataFrame(columns=["kappa", "branch", "symmetry", "Omega"])
        return pd.concat(frames, ignore_index=True)
