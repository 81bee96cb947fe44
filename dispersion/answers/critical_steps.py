"""Critical steps of central differences for several mass rules: ``dispersion timestep`` as a
function.

:func:`critical_steps` computes :func:`~dispersion.waves.timestep.critical_step` for each rule
(default: every registered rule that applies to the model) on one discretization and returns
:class:`CriticalSteps`: one row per rule with the largest discrete frequency over the
Brillouin zone, where it lies, the critical step :math:`\\Delta t_{crit} = 2/\\omega_{max}`
in seconds and its ratio to the consistent mass's. The setting (model, sizes, material) is
stated once, in the header, with every symbol defined.

>>> t = critical_steps(["consistent", "lumped"], 1, model="bar", wave_speed=1.0)
>>> [(r["mass"], r["omega_max h / c"], round(r["ratio to consistent"], 6)) for r in t.rows()]
[('consistent', 3.4641016151377544, 1.0), ('lumped', 2.0, 1.732051)]

References
----------
T. J. R. Hughes, *The Finite Element Method*, Dover 2000, sec. 9.3 (stability of central
differences, :math:`\\Delta t \\le 2/\\omega_{max}`).
"""
from __future__ import annotations

from dataclasses import dataclass

from dispersion import defaults
from dispersion.rendering import Rendered

__all__ = ["CriticalSteps", "critical_steps", "default_rules"]


@dataclass(frozen=True, repr=False)  # Rendered: short repr; every format from the steps
class CriticalSteps(Rendered):
    """One :class:`~dispersion.waves.timestep.CriticalStep` per rule, on one setting."""

    steps: tuple
    model: str
    material: object
    certify: bool = False
    contact: str | None = None
    gamma_s: object = None

    @property
    def failures(self) -> tuple[str, ...]:
        """Every step's failures (a proof that did not close), named by its rule."""
        return tuple(f"mass {s.mass}: {why}" for s in self.steps for why in s.failures)

    @property
    def _unit(self) -> str:
        return "omega_max h / c" if self.model == "bar" else "omega_max H / c_T"

    def title(self) -> str:
        s = self.steps[0]
        where = (f"periodic 1D bar, p = {s.p}" if self.model == "bar" else
                 f"Bloch plate patch, p = {s.p}, n = {s.n}")
        return (f"Critical time step of central differences: {where}, h = {s.h:g} m, "
                f"{'c = ' + format(s.wave_speed, 'g') + ' m/s' if s.material is None else s.material}")

    def header_lines(self) -> list[str]:
        s = self.steps[0]
        if self.model == "bar":
            lines = [f"model: the periodic 1D bar of degree p = {s.p}, element length "
                     f"h = {s.h:g} m, wave speed c = {s.wave_speed:g} m/s",
                     "omega_max h / c: the largest discrete frequency over the Brillouin "
                     "zone theta in [0, pi] (theta = k h), dimensionless"]
        else:
            H = (s.n - s.p) * s.h / 2
            lines = [f"model: the Bloch plate patch in plane strain, degree p = {s.p}, n = {s.n} "
                     f"control points through the thickness, square elements of edge "
                     f"h = {s.h:g} m",
                     f"H: half the plate thickness, H = (n - p) h / 2 = {H:g} m; aspect ratio "
                     f"r = b/H = {s.r}",
                     "omega_max H / c_T: the largest discrete frequency over the Brillouin "
                     "zone theta in [0, pi] (theta = k b, b the element length along the "
                     "plate), dimensionless; c_T the shear wave speed"]
        if self.contact is not None:
            lines.append(f"singular rules: contact set {self.contact}, gamma_s = "
                         f"{self.gamma_s} (the share sent to the second neighbour)")
        if self.material is not None and s.material is not None:
            lines.append(f"material: {self.material.describe()}")
        lines.append("dt_crit = 2 / omega_max in s: the largest stable step of central "
                     "differences; ratio: dt_crit over the consistent mass's")
        lines.append("theta: the phase where omega_max lies; found: how (exact: a closed form; "
                     "numeric: the largest over a grid of phases, refined)")
        return lines

    def columns(self) -> tuple[str, ...]:
        cols = ("mass", self._unit, "exact value", "theta", "found", "dt_crit [s]",
                "ratio to consistent")
        if self.certify:
            cols += (f"{self._unit} proven bound", "proven stable dt [s]")
        return cols

    def text_columns(self) -> tuple[str, ...]:
        return tuple(c for c in self.columns() if c not in ("exact value", "found"))

    def rows(self) -> list[dict]:
        out = []
        for s in self.steps:
            row = {"mass": s.mass, self._unit: s.omega_max,
                   "exact value": None if s.omega_max_exact is None else str(s.omega_max_exact),
                   "theta": s.theta, "found": s.method, "dt_crit [s]": s.dt,
                   "ratio to consistent": s.ratio}
            if self.certify:
                row.update({f"{self._unit} proven bound": s.omega_certified,
                            "proven stable dt [s]": s.dt_certified})
            out.append(row)
        return out


def default_rules(model: str) -> tuple[str, ...]:
    """Every registered rule that applies to ``model``: the Bloch plate takes the rules with
    one B-spline symbol along x (:data:`~dispersion.symbolic.mass_rule.BLOCH_RULE_NAMES`); the
    bar has no contact set, so the singular rules (and rules with zero rows) are left out
    there."""
    from dispersion.mass_rules.mass_rule import BLOCH_RULE_NAMES, RULE_NAMES, get_rule

    if model != "bar":
        return BLOCH_RULE_NAMES
    return tuple(r for r in RULE_NAMES
                 if not (get_rule(r).redistributes or get_rule(r).states.zero_rows))


def critical_steps(masses=None, p: int = 2, *, model: str = "plate", material="steel",
                   h: float = 1.0, n: int | None = None, wave_speed: float | None = None,
                   contact: str = "top", gamma_s=None, certify: bool = False) -> CriticalSteps:
    """Critical steps of ``masses`` (names or rules; default :func:`default_rules`) on one
    setting; the parameters are those of :func:`dispersion.waves.timestep.critical_step`."""
    from dispersion.errors import InputError
    from dispersion.materials.materials import MATERIALS, Material
    from dispersion.time_stepping.timestep import critical_step

    if isinstance(material, str):
        from dispersion.materials.materials import material as by_name

        material = by_name(material)
    if not isinstance(material, Material):
        raise InputError(f"material must be a Material or one of {', '.join(MATERIALS)}")
    rules = default_rules(model) if masses is None else tuple(masses)
    if not rules:
        raise InputError("masses must name at least one mass rule")
    from dispersion.mass_rules.mass_rule import get_rule

    gamma_s = defaults.text("GAMMA_S") if gamma_s is None else gamma_s
    steps = tuple(critical_step(rule, p, model=model, material=material, h=h, n=n,
                                wave_speed=wave_speed, contact=contact, certify=certify,
                                gamma_s=_exact(gamma_s)) for rule in rules)
    singular = model == "plate" and any(get_rule(r).redistributes for r in rules)
    return CriticalSteps(steps, model, material, bool(certify),
                         contact if singular else None, gamma_s if singular else None)


def _exact(value):
    """A gamma_s as the exact number the patch takes (``"1/2"`` -> 1/2)."""
    from dispersion.reader import read_number

    return read_number(value) if isinstance(value, str) else value
