"""The S0/A0 series as one answer: ``dispersion series`` as a function.

:func:`series_table` derives the Taylor coefficients of :math:`\\Omega^2` in :math:`\\kappa`
of the branches through the origin, of the exact Rayleigh-Lamb equation (eqs 14-15,
:func:`~dispersion.continuum.exact_series.exact_series_raw`) or of a discrete patch (eqs 17-20,
:func:`~dispersion.symbolic.power_balance.discrete_series_raw`: one determinant for both
branches where the mass breaks the mirror), with Poisson's ratio symbolic or substituted, and
returns a :class:`SeriesTable`. The table prints from the flint kernel alone
(:func:`~dispersion.symbolic.power_balance.format_coefficient`): the exact series needs
neither sympy nor numpy; LaTeX (:meth:`SeriesTable.to_latex`) reads the text back with the
whitelist reader (:mod:`dispersion.reader`), never with sympy's parser.

>>> t = series_table(("A0",), 6, exact=True)
>>> t
<SeriesTable: Omega^2 series of A0, exact Rayleigh-Lamb, nu symbolic, to kappa^6 (2 rows)>
>>> print(t.to_text())
Omega_A0^2 [exact Rayleigh-Lamb] =
  + (-2/(3*(nu - 1))) * kappa^4
  + (2*(7*nu - 17)/(45*(nu - 1)**2)) * kappa^6
  + O(kappa^8)

References
----------
A. Tkachuk, M. Matzen, R. Kolman, M. Bischoff, eqs (14)-(20).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from dispersion.rendering import Rendered

__all__ = ["ORDER", "SeriesTable", "series_table", "order_range"]

#: Default highest power of kappa (the printed eqs 17-20 stop at kappa^8).
ORDER = 8


def order_range() -> str:
    """The orders a request may ask for, in words (the bounds of
    :func:`dispersion.symbolic.power_balance.check_request`).

    >>> order_range()
    '(an even power of kappa) in [2, 32], or [2, 128] for the exact series'
    """
    from dispersion.symbolic.power_balance import MAX_ORDER

    return (f"(an even power of kappa) in [2, {MAX_ORDER['discrete']}], or [2, "
            f"{MAX_ORDER['exact']}] for the exact series")


@dataclass(frozen=True, repr=False)  # Rendered: short repr; every format from the records
class SeriesTable(Rendered):
    """Series of ``branches`` to ``kappa^order``: ``records`` (the JSON interface, one per
    branch: ``branch, mass, model, coefficients`` and the patch fields that apply), computed
    from ``patch`` (None: the exact equation) with the elastic ``law`` whose numbers are
    substituted (an isotropic law with nu None: symbolic)."""

    branches: tuple[str, ...]
    order: int
    patch: Any
    law: Any
    records: tuple[dict, ...]

    @property
    def nu(self):
        """Poisson's ratio substituted (None: symbolic, or a law without one)."""
        return getattr(self.law, "nu", None)

    def _model(self) -> str:
        if self.patch is None:
            return "exact Rayleigh-Lamb"
        return f"{self.patch.geometry_title()}, {self.patch.mass_title()}"

    def _material(self) -> str:
        if self.law.kind != "isotropic":
            return self.law.describe()
        return "nu symbolic" if self.nu is None else f"nu = {self.nu}"

    def title(self) -> str:
        return (f"Omega^2 series of {' and '.join(self.branches)}, {self._model()}, "
                f"{self._material()}, to kappa^{self.order}")

    def header_lines(self) -> list[str]:
        lines = ["Omega = omega h / c_T, kappa = k h (h: half the thickness); Omega^2 as a "
                 "power series in kappa", f"model: {self._model()}"]
        if self.law.kind != "isotropic":
            lines.append(f"material: {self.law.describe()}")
        else:
            lines.append("nu: symbolic (coefficients are rational functions of nu)"
                         if self.nu is None else f"nu: {self.nu}")
        if self.patch is not None and self.patch.symbolic_r:
            lines.append("r: symbolic (the aspect ratio b/h of the Bloch model)")
        return lines

    def columns(self) -> tuple[str, ...]:
        return ("branch", "power", "coefficient")

    def rows(self) -> list[dict]:
        return [{"branch": r["branch"], "power": int(k), "coefficient": c}
                for r in self.records for k, c in r["coefficients"].items()]

    def to_dict(self):
        """The documented interface: one record ``{"branch", "mass", "model",
        "coefficients": {"2": "...", ...}}`` for one branch, a list for both; each
        coefficient sympy-parsable text. (An exact derivation has no failures to carry.)"""
        return dict(self.records[0]) if len(self.records) == 1 else [dict(r) for r in self.records]

    def to_text(self, digits: int = 7) -> str:
        """The series as formulas, one block per branch."""
        blocks = []
        for r in self.records:
            terms = list(r["coefficients"].items())
            lines = [f"Omega_{r['branch']}^2 [{self._model()}] ="]
            lines += [f"  + ({c}) * kappa^{k}" for k, c in terms]
            blocks.append("\n".join(lines + [f"  + O(kappa^{int(terms[-1][0]) + 2})"]))
        return "\n\n".join(blocks)

    def to_latex(self) -> str:
        """Each branch as a LaTeX equation, the factored forms of the text kept."""
        import sympy

        from dispersion.reader import SERIES_TEXT, parse, to_sympy

        out = []
        for r in self.records:
            terms = list(r["coefficients"].items())
            # read by the whitelist (records are data: a table may be built from JSON), built
            # unevaluated: 2/(3*(nu - 1)) stays so, not 2/(3 nu - 3)
            body = " + ".join(
                f"\\left({sympy.latex(to_sympy(parse(c, limits=SERIES_TEXT), evaluate=False))}"
                f"\\right)\\kappa^{{{k}}}" for k, c in terms)
            last = int(terms[-1][0])
            out.append(f"% Omega_{r['branch']}^2 [{self._model()}]\n"
                       f"\\Omega_{{{r['branch']}}}^2 = {body} + "
                       f"O(\\kappa^{{{last + 2}}})")
        return "\n\n".join(out)


def series_table(branches=("S0", "A0"), order: int = ORDER, *, patch=None,
                 exact: bool = False, nu=None) -> SeriesTable:
    """Series of ``branches`` to ``kappa^order`` (see the module docstring).

    ``patch``: the discrete :class:`~dispersion.symbolic.patch.Patch` (default: the toolkit's;
    with ``exact=True`` none may be given), derived with its elastic law; ``nu``: a rational
    value substituted for Poisson's ratio (None: the patch's, else symbolic). Bounds:
    :func:`dispersion.symbolic.power_balance.check_request`.
    """
    from dispersion.errors import InputError
    from dispersion.materials.elastic_law import as_law

    branches = (branches,) if isinstance(branches, str) else tuple(branches)
    if isinstance(nu, str):  # "3/10" as the command line reads it, by the whitelist
        from dispersion.reader import read_number

        try:
            nu = read_number(nu)
        except InputError as exc:
            raise InputError(f"nu must be a rational number such as 3/10, got "
                             f"{nu[:40]!r} ({exc})") from None
    if exact:
        if patch is not None:
            raise InputError("patch does not apply with exact=True (the exact Rayleigh-Lamb "
                             "series has no discrete patch)")
        from dispersion.continuum.exact_series import exact_series_raw

        raws = {b: exact_series_raw(b, order) for b in branches}
        law = as_law(nu)
    else:
        from dispersion.symbolic.patch import Patch
        from dispersion.symbolic.power_balance import discrete_series_raw

        patch = Patch() if patch is None else patch
        law = patch.law
        if nu is not None:  # the number as given (a float: its binary value, exact)
            if not patch.isotropic or patch.nu not in (None, patch.replace(nu=nu).nu):
                raise InputError(f"nu = {nu} given for a patch of another material "
                                 f"({patch.law.describe()}): give one")
            law = as_law(nu)
        raws = discrete_series_raw(branches, order, patch)[0]
    records = tuple(_record(b, raws[b], patch, law) for b in branches)
    return SeriesTable(branches, int(order), patch, law, records)


def _record(branch: str, raw, patch, law) -> dict:
    from dispersion.symbolic.power_balance import format_coefficient, substitute_raw

    for name, value in law.substitutions().items():
        raw = substitute_raw(raw, name, value)
    if patch is None:
        mass, model = "exact", "rayleigh-lamb"
    else:
        mass = patch.mass_name
        model = patch.model if patch.model == "x-exact" else f"bloch r={patch.r}"
    record = {"branch": branch, "mass": mass, "model": model,
              "coefficients": {str(k): format_coefficient(a, b) for k, a, b in raw}}
    if patch is not None:
        record.update(p=patch.p, n=patch.n)
        if patch.singular:
            record.update(contact=patch.contact, gamma_s=str(patch.gamma_s))
    if law.kind != "isotropic":
        record["law"] = law.as_dict()
    elif law.nu is not None:
        record["nu"] = str(law.nu)
    return record
