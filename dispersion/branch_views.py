"""How a set of branches on a kappa grid shows itself: short reprs, HTML, a DataFrame.

:class:`BranchViews` is mixed into :class:`~dispersion.discretization.discrete_branches.DiscreteBranches`
and :class:`~dispersion.continuum.exact_branches.ExactBranches` (both hold ``kappa`` and
``omega[label]``). A repr names the grid and the branches, never whole arrays, so a notebook
cell or a log line stays short; ``to_dataframe()`` gives the long table (one row per kappa and
branch) when pandas is installed (the ``dataframe`` extra).

>>> import numpy as np
>>> from dispersion.continuum.exact_branches import ExactBranches
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

from dispersion.rendering import DATAFRAME_EXTRA, Rendered, require_pandas

__all__ = ["BranchViews", "DATAFRAME_EXTRA", "require_pandas"]

def _g(x) -> str:
    return "nan" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.4g}"


class BranchViews(Rendered):
    """Short ``repr``, ``_repr_html_``, and the rendering protocol of a branch set (see module)."""

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

    # ------------------------------------------------------------------ the rendering protocol

    def title(self) -> str:
        what = {"ExactBranches": "exact Rayleigh-Lamb branches",
                "DiscreteBranches": "discrete branches"}.get(type(self).__name__, "branches")
        return f"{what}: {', '.join(self._facts()[:-1])}"

    def header_lines(self) -> list[str]:
        lines = ["kappa = k h, Omega = omega h / c_T (h: half the thickness)"]
        if getattr(self, "zone_edge", None) is not None:
            lines.append(f"Bloch zone edge: kappa = pi/r = {_g(self.zone_edge)} (beyond it the "
                         "branches are folded)")
        if getattr(self, "group", None):
            lines.append("c_g/c_T: group velocity over the shear wave speed")
        return lines

    def columns(self) -> tuple[str, ...]:
        cols = ("kappa", "branch", "symmetry", "Omega")
        return cols + (("c_g/c_T",) if getattr(self, "group", None) else ())

    def rows(self) -> list[dict]:
        """One row per (kappa, branch) where the branch exists: ``kappa, branch, symmetry,
        Omega`` and, where computed, ``c_g/c_T`` (group velocity over the shear speed)."""
        kappa = np.asarray(self.kappa, dtype=float)
        group = getattr(self, "group", None) or {}
        out = []
        for label, w in self.omega.items():
            w = np.asarray(w, dtype=float)
            sym = self._symmetry_of(label)
            g = np.asarray(group.get(label, np.full(kappa.shape, np.nan)), dtype=float)
            for i in np.flatnonzero(np.isfinite(w)):
                row = {"kappa": float(kappa[i]), "branch": label, "symmetry": sym,
                       "Omega": float(w[i])}
                if group:
                    row["c_g/c_T"] = float(g[i])
                out.append(row)
        return out
