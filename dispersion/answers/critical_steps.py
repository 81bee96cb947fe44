"""Critical steps of central differences for several mass rules: ``dispersion timestep`` as a
function.

:func:`critical_steps` computes :func:`~dispersion.time_stepping.timestep.critical_step` for each rule
(default: every registered rule that applies to the model) on one discretization and returns
:class:`CriticalSteps`: one row per rule with the largest discrete frequency over the
Brillouin zone, where it lies, the critical step :math:`\\Delta t_{crit} = 2/\\omega_{max}`
in seconds and its ratio to the consistent mass's. The setting (model, sizes, material) is
stated once, in the header, with every symbol defined.

>>> t = critical_steps(["consistent", "lumped"], 1, model="bar", wave_speed=1.0)
>>> [(r["mass"], r["lattice omega_max h / c"], round(r["ratio to consistent"], 6)) for r in t.rows()]
[('consistent', 3.4641016151377544, 1.0), ('lumped', 2.0, 1.732051)]

These are the periodic lattice's (an infinite or periodic mesh). With ``elements`` a finite
mesh of that many elements and ``ends`` (open knot vectors) is measured beside it
(:func:`dispersion.time_stepping.mesh_step.mesh_omega_max`): its largest frequency and a
*proven* upper bound; the step a finite mesh may use is the mesh's:

>>> m = critical_steps(["lumped"], 2, model="bar", wave_speed=1.0, elements=60, ends="free")
>>> row = m.rows()[0]
>>> round(row["mesh omega_max h / c"], 4), row["mesh dt_crit [s]"] < row["lattice dt_crit [s]"]
(2.32, True)

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
    """One :class:`~dispersion.time_stepping.timestep.CriticalStep` per rule, on one setting."""

    steps: tuple
    model: str
    material: object
    certify: bool = False
    contact: str | None = None
    gamma_s: object = None
    #: Default rules left out, each ``(rule, why)``: a rule of the registry that has no
    #: critical step on this setting (indefinite at this degree, say); a rule the user named
    #: is never skipped, it is refused.
    skipped: tuple = ()
    #: The finite mesh measured beside each lattice row
    #: (:class:`~dispersion.time_stepping.mesh_step.MeshOmegaMax` or the reason it is not),
    #: and its patch's words; empty without ``elements``.
    meshes: tuple = ()
    mesh_setting: str | None = None

    def _mesh_failures(self) -> tuple[str, ...]:
        return tuple(f"mass {s.mass}: mesh: {m}" for s, m in zip(self.steps, self.meshes)
                     if isinstance(m, str))

    @property
    def failures(self) -> tuple[str, ...]:
        """Every step's failures (a proof that did not close), named by its rule."""
        return tuple(f"mass {s.mass}: {why}" for s in self.steps for why in s.failures) \
            + self._mesh_failures()

    @property
    def _unit(self) -> str:
        return "omega_max h / c" if self.model == "bar" else "omega_max H / c_T"

    def title(self) -> str:
        s = self.steps[0]
        where = (f"periodic 1D bar, p = {s.p}" if self.model == "bar" else
                 f"Bloch plate patch, p = {s.p}, n = {s.n}")
        if self.meshes:
            where += f"; and its finite mesh ({self.mesh_setting})"
        return (f"Critical time step of central differences: {where}, h = {s.h:g} m, "
                f"{'c = ' + format(s.wave_speed, 'g') + ' m/s' if s.material is None else s.material}")

    def header_lines(self) -> list[str]:
        s = self.steps[0]
        if self.model == "bar":
            lines = [f"model: the periodic 1D bar of degree p = {s.p}, element length "
                     f"h = {s.h:g} m, wave speed c = {s.wave_speed:g} m/s",
                     "lattice omega_max h / c: the periodic lattice's largest discrete "
                     "frequency over the Brillouin zone theta in [0, pi] (theta = k h), "
                     "dimensionless"]
        else:
            H = (s.n - s.p) * s.h / 2
            lines = [f"model: the Bloch plate patch in plane strain, degree p = {s.p}, n = {s.n} "
                     f"control points through the thickness, square elements of edge "
                     f"h = {s.h:g} m",
                     f"H: half the plate thickness, H = (n - p) h / 2 = {H:g} m; aspect ratio "
                     f"r = b/H = {s.r}",
                     "lattice omega_max H / c_T: the periodic lattice's largest discrete "
                     "frequency over the Brillouin zone theta in [0, pi] (theta = k b, b the "
                     "element length along the plate), dimensionless; c_T the shear wave "
                     "speed"]
        if self.contact is not None:
            lines.append(f"singular rules: contact set {self.contact}, gamma_s = "
                         f"{self.gamma_s} (the share sent to the second neighbour)")
        if self.material is not None and s.material is not None:
            lines.append(f"material: {self.material.describe()}")
        lines.append("lattice dt_crit = 2 / omega_max in s: the largest stable step of central "
                     "differences on the periodic lattice (an infinite or periodic mesh); "
                     "ratio: dt_crit over the consistent mass's")
        if self.meshes:
            lines.append(f"mesh: {self.mesh_setting}; mesh omega_max: its largest frequency "
                         "(Lanczos, then bisection on the inertia: a Rayleigh quotient, a "
                         "lower bound); proven bound: an upper bound proven by a verified "
                         "Cholesky factorization of sigma M - K (Rump 2006)")
            lines.append("mesh dt_crit = 2 / (proven bound) in s: the step this mesh may use "
                         "(stable, proven); a finite mesh must not use the lattice's dt_crit, "
                         "which its boundary outliers can exceed")
        else:
            lines.append("a finite mesh has boundary outliers and may need a smaller step: "
                         "--elements N gives that mesh's own proven step")
        lines.append("theta: the phase where omega_max lies; found: how (exact: a closed form; "
                     "numeric: the largest over a grid of phases, refined)")
        lines += [f"skipped: mass {name}: {why}" for name, why in self.skipped]
        return lines

    def columns(self) -> tuple[str, ...]:
        cols = ("mass", f"lattice {self._unit}", "exact value", "theta", "found",
                "lattice dt_crit [s]", "ratio to consistent")
        if self.certify:
            cols += (f"lattice {self._unit} proven bound", "lattice proven stable dt [s]")
        if self.meshes:
            cols += (f"mesh {self._unit}", f"mesh {self._unit} proven bound",
                     "mesh dt_crit [s]", "mesh / lattice dt")
        return cols

    def text_columns(self) -> tuple[str, ...]:
        return tuple(c for c in self.columns() if c not in ("exact value", "found"))

    def rows(self) -> list[dict]:
        out = []
        for i, s in enumerate(self.steps):
            row = {"mass": s.mass, f"lattice {self._unit}": s.omega_max,
                   "exact value": None if s.omega_max_exact is None else str(s.omega_max_exact),
                   "theta": s.theta, "found": s.method, "lattice dt_crit [s]": s.dt,
                   "ratio to consistent": s.ratio}
            if self.certify:
                row.update({f"lattice {self._unit} proven bound": s.omega_certified,
                            "lattice proven stable dt [s]": s.dt_certified})
            if self.meshes:
                m = self.meshes[i]
                ok = not isinstance(m, str) and m.omega_proven is not None
                dt = s.dt * s.omega_max / m.omega_proven if ok else None
                row.update({f"mesh {self._unit}": None if isinstance(m, str) else m.omega,
                            f"mesh {self._unit} proven bound": m.omega_proven if ok else None,
                            "mesh dt_crit [s]": dt,
                            "mesh / lattice dt": dt / s.dt if ok else None})
            out.append(row)
        return out


def default_rules(model: str) -> tuple[str, ...]:
    """Every registered rule that applies to ``model``: the Bloch plate takes the rules with
    one B-spline symbol along x (:data:`~dispersion.mass_rules.mass_rule.BLOCH_RULE_NAMES`); the
    bar has no contact set, so the singular rules (and rules with zero rows) are left out
    there."""
    from dispersion.mass_rules.mass_rule import BLOCH_RULE_NAMES, RULE_NAMES, get_rule

    if model != "bar":
        return BLOCH_RULE_NAMES
    return tuple(r for r in RULE_NAMES
                 if not (get_rule(r).redistributes or get_rule(r).states.zero_rows))


def critical_steps(masses=None, p: int = 2, *, model: str = "plate", material="steel",
                   h: float = 1.0, n: int | None = None, wave_speed: float | None = None,
                   contact: str = "top", gamma_s=None, certify: bool = False,
                   elements: int | None = None, ends="free") -> CriticalSteps:
    """Critical steps of ``masses`` (names or rules; default :func:`default_rules`) on one
    setting; the parameters are those of :func:`dispersion.time_stepping.timestep.critical_step`.
    ``elements``: also the finite mesh of that many elements with ``ends`` (free, fixed,
    sliding or periodic, or a pair), its largest frequency and proven step."""
    from dispersion.errors import InputError
    from dispersion.materials.materials import MATERIALS, Material

    if isinstance(material, str):
        from dispersion.materials.materials import material as by_name

        material = by_name(material)
    if not isinstance(material, Material):
        raise InputError(f"material must be a Material or one of {', '.join(MATERIALS)}")
    if isinstance(masses, str) or hasattr(masses, "build"):  # one rule, not its letters
        masses = (masses,)
    rules = default_rules(model) if masses is None else tuple(masses)
    if not rules:
        raise InputError("masses must name at least one mass rule")
    from dispersion.mass_rules.mass_rule import get_rule

    gamma_s = defaults.text("GAMMA_S") if gamma_s is None else gamma_s
    steps, kept, skipped = [], [], []
    for rule in rules:
        try:
            steps.append(_step(rule, p, model=model, material=material, h=h, n=n,
                               wave_speed=wave_speed, contact=contact, certify=certify,
                               gamma_s=_exact(gamma_s)))
            kept.append(rule)
        except _NoStep as exc:
            if masses is not None:  # named by the user: refused, not skipped
                raise InputError(f"the mass rule {_name(rule)!r} has no critical step at "
                                 f"p = {p}: {exc}") from None
            skipped.append((_name(rule), f"no critical step at p = {p}: {exc}"))
    if not steps:
        raise InputError(f"no default mass rule has a critical step at p = {p}: "
                         + "; ".join(f"{name}: {why}" for name, why in skipped))
    singular = model == "plate" and any(get_rule(r).redistributes for r in kept)
    meshes, setting = (), None
    if elements is not None:
        meshes, setting = _meshes(kept, steps, model, elements, ends, contact,
                                  _exact(gamma_s))
    return CriticalSteps(tuple(steps), model, material, bool(certify),
                         contact if singular else None, gamma_s if singular else None,
                         tuple(skipped), meshes, setting)


class _NoStep(Exception):
    """A rule without a critical step on the setting (its mass is indefinite)."""


def _reason(message) -> str:
    """A rule's warning without its "mass rule 'name': " prefix (the caller names the rule)."""
    import re

    return re.sub(r"^mass rule '[^']*': ", "", str(message))


def _name(rule) -> str:
    return getattr(rule, "name", rule)


def _step(rule, p, **setting):
    """:func:`~dispersion.time_stepping.timestep.critical_step`, with an indefinite mass (warned by
    the rule's check, or met by the Cholesky factorization) raised as :class:`_NoStep`."""
    import warnings

    from dispersion.errors import IndefiniteMassWarning, InputError
    from dispersion.time_stepping.timestep import critical_step

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            step = critical_step(rule, p, **setting)
        except InputError as exc:
            if "not positive definite" not in str(exc):
                raise
            why = [_reason(w.message) for w in caught if issubclass(w.category,
                                                                    IndefiniteMassWarning)]
            raise _NoStep(why[0] if why else str(exc)) from None
    for w in caught:
        if issubclass(w.category, IndefiniteMassWarning):
            raise _NoStep(_reason(w.message))
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    return step


def _meshes(rules, steps, model, elements, ends, contact, gamma_s) -> tuple[tuple, str]:
    """The finite mesh beside each lattice row: its largest frequency bracketed, or why not."""
    from dispersion.discretization.finite_mesh.finite_patch import finite_bar, finite_strip
    from dispersion.time_stepping.mesh_step import mesh_omega_max
    from dispersion.errors import ConvergenceError, InputError, check_int_in_range

    elements = check_int_in_range("elements", elements, 1, 10**6)
    first = steps[0]
    out, label = [], None
    for rule, s in zip(rules, steps):
        try:
            if model == "bar":
                patch = finite_bar(s.p, elements, ends=ends, mass=rule, length=float(elements),
                                   gamma_s=float(gamma_s))
            else:
                patch = finite_strip(s.p, elements, n=s.n, ends=ends, mass=rule, nu=float(s.nu),
                                     length=elements * float(s.r), contact=contact,
                                     gamma_s=float(gamma_s))
        except InputError as exc:
            if rule == rules[0]:
                raise  # a setting no rule can take (the ends, the size): the caller's error
            out.append(f"not built ({exc})")
            continue
        try:
            out.append(mesh_omega_max(patch))
        except (InputError, ConvergenceError) as exc:
            out.append(f"not measured ({exc})")
        label = label or patch
    what = "bar" if model == "bar" else (f"plate strip (plane strain, {first.n} control points "
                                         "through the thickness, square elements)")
    words = "" if label is None else (
        f"the finite {what} of {elements} elements, "
        f"{'periodic' if label.periodic else '-'.join(label.ends)} ends, open knot vectors")
    return tuple(out), words


def _exact(value):
    """A gamma_s as the exact number the patch takes (``"1/2"`` -> 1/2)."""
    from dispersion.reader import read_number

    return read_number(value) if isinstance(value, str) else value
