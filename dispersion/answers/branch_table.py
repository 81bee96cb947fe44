"""The branches on a kappa grid as one answer: ``dispersion branches`` as a function.

:func:`branch_table` takes the request (the discrete patch and its mass rules, Poisson's ratio
or a material and a thickness, the kappa grid, the largest Omega, optionally a Newmark member
and a Courant number), checks it against the bounds stated here before any work, and returns a
:class:`BranchTable`: the exact Rayleigh-Lamb branches with their velocities, every discrete
(or fully discrete) branch set, in physical units where a material is given, with the ZGV
points and every value that could not be certified. The table renders itself
(:class:`dispersion.rendering.Rendered`): rows, CSV, JSON, text and its figure
(:func:`dispersion.plotting.branches.figure_branch_table`) are drawn from it, so the command
line, :meth:`dispersion.patch_model.PatchModel.branches` and a notebook share the bounds, the
grid and the labels.

Rows: ``kappa, Omega, branch, symmetry, source, c_p/c_T, c_g/c_T`` (kappa = kh,
Omega = omega h / c_T, h the half-thickness) and, with a material, ``f [kHz], fd [MHz mm],
c_p [m/s], c_g [m/s], wavelength [mm]``.

>>> t = branch_table(exact=True, kappa_max=2.0, count=3, omega_max=3.0)
>>> t
<BranchTable: Rayleigh-Lamb branches, nu = 0.3, 3 kappa in [0, 2], Omega <= 3 (10 rows)>
>>> [(r["branch"], round(r["Omega"], 6)) for r in t.rows() if r["kappa"] == 1.0]
[('S0', 1.615387), ('S1', 2.745989), ('A0', 0.650345), ('A1', 2.32629)]

References
----------
A. Tkachuk, M. Matzen, R. Kolman, M. Bischoff, Figure 2 and eqs (5), (13); J. L. Rose,
*Ultrasonic waves in solid media*, 2004, ch. 8 (units of the practitioner).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from dispersion import defaults
from dispersion.budget import DISCRETE_N_MAX, DISCRETE_WORK_MAX, check_discrete_branches
from dispersion.errors import InputError
from dispersion.rendering import Rendered

if TYPE_CHECKING:  # numpy and the solvers load when a table is computed, not on import
    import numpy as np

    from dispersion.symbolic.patch import Patch
    from dispersion.continuum.exact_branches import ExactBranches
    from dispersion.materials.materials import Material
    from dispersion.continuum.velocities import Velocities

__all__ = ["MAX_COUNT", "MAX_OMEGA", "MAX_DISCRETE_WORK", "DISCRETE_N_MAX", "KAPPA_MIN",
           "KAPPA_MAX", "COUNT", "OMEGA_MAX", "DEFAULT_MASSES", "COURANT_MAX", "BranchTable",
           "branch_table", "kappa_grid", "check_discrete_work"]

#: Most kappa points of one request (the tracer's own scan bound applies as well:
#: :data:`dispersion.continuum.exact_branches.MAX_SAMPLES`, count * (omega_max / 0.05 + 1)).
MAX_COUNT = 200_000
#: Largest Omega = omega h / c_T of a request.
MAX_OMEGA = 200.0
#: Discrete branches: count * (mass rules) * n^3 <= MAX_DISCRETE_WORK (the rule and its
#: measurements: :data:`dispersion.budget.DISCRETE_WORK_MAX`, rule 6 of :mod:`dispersion.budget`).
MAX_DISCRETE_WORK = DISCRETE_WORK_MAX
#: The default grid and ceiling: Figure 2's axes.
KAPPA_MIN, KAPPA_MAX, COUNT, OMEGA_MAX = 0.0, 8.0, 400, 8.0
#: The mass rules compared when none is named (Figure 2).
DEFAULT_MASSES = ("consistent", "singular")
#: Largest Courant number (step over the critical step) of an implicit Newmark member; an
#: explicit one is stable only up to 1.
COURANT_MAX = 10.0


def kappa_grid(kappa_min: float = KAPPA_MIN, kappa_max: float = KAPPA_MAX,
               count: int = COUNT) -> np.ndarray:
    """The uniform grid of ``count`` kappa in ``[kappa_min, kappa_max]``, checked.

    >>> kappa_grid(0, 1, 3).tolist()
    [0.0, 0.5, 1.0]
    >>> kappa_grid(1, 1, 3)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: kappa_max must exceed kappa_min >= 0, got [1, 1]
    """
    for name, v in (("kappa_min", kappa_min), ("kappa_max", kappa_max)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise InputError(f"{name} must be a finite number, got {v!r}")
    if kappa_min < 0 or not kappa_max > kappa_min:
        raise InputError(f"kappa_max must exceed kappa_min >= 0, got [{kappa_min:g}, "
                         f"{kappa_max:g}]")
    if isinstance(count, bool) or not isinstance(count, int) or not 2 <= count <= MAX_COUNT:
        raise InputError(f"count must be an integer in [2, {MAX_COUNT}], got {count!r}")
    import numpy as np

    return np.linspace(float(kappa_min), float(kappa_max), count)


def check_discrete_work(count: int, masses: int, n: int) -> int:
    """Refuse, before any work, discrete branches costing more than
    :data:`MAX_DISCRETE_WORK` (``count * masses * n^3``, rule 6a of :mod:`dispersion.budget`;
    the whole rule, with the setup of each mass rule: :func:`~dispersion.budget.check_discrete_branches`);
    returns the work.

    >>> check_discrete_work(400, 2, 30)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: count * (mass rules) * n^3 must be <= 11059200 (about a minute), got 21600000: at most count = 204 at n = 30 with 2 mass rule(s)
    """
    return check_discrete_branches(count, ["consistent"] * int(masses), 1, max(int(n), 2))


def _name(mass) -> str:
    return getattr(mass, "name", mass)


@dataclass(frozen=True)
class DiscreteSet:
    """One discrete branch set of a table: its ``name`` (the mass rule, and the scheme when
    fully discrete), the ``patch`` it was computed on, the branches and, for fully discrete
    ones, the time step ``tau`` (in h / c_T) and the shape-paired errors when asked for."""

    name: str
    patch: Any
    branches: Any
    tau: float | None = None
    paired_error: dict | None = None
    #: Per exact label, the discrete partner of each kappa (-1: none; see paired_error).
    paired_partner: dict | None = None

    def words(self) -> str:
        """The set in words: its mass rule with what applies to it, and its time scheme."""
        text = _mass_words(self.patch)
        return text if self.tau is None else f"{text}, {self.name.split(' ', 1)[1]}"


@dataclass(frozen=True, repr=False)
class BranchTable(Rendered):
    """Exact and discrete branches on one kappa grid, with what they were computed from.

    ``discrete`` holds one :class:`DiscreteSet` per mass rule (empty for the exact branches
    alone); ``material`` and ``thickness_mm`` put the rows in units; ``zgv`` are the exact
    branches' zero-group-velocity points (with a material).
    """

    nu: float
    kappa: np.ndarray
    omega_max: float
    exact: ExactBranches
    velocities: Velocities
    discrete: tuple[DiscreteSet, ...] = ()
    base_patch: Patch | None = None
    material: Material | None = None
    thickness_mm: float | None = None
    scheme: str | None = None
    courant: float | None = None
    zgv: tuple = ()
    failures: tuple[str, ...] = field(default=())

    # ------------------------------------------------------------------ labels

    def title(self) -> str:
        what = "Rayleigh-Lamb branches"
        if self.discrete:
            kind = "fully discrete" if self.scheme else "discrete"
            what = (f"Rayleigh-Lamb and {kind} branches of the "
                    f"{self.base_patch.geometry_title()} patch")
        k = self.kappa
        plate = (f"{self.material.name}, d = {self.thickness_mm:g} mm" if self.material
                 else f"nu = {self.nu:g}")
        return (f"{what}, {plate}, {k.size} kappa in [{k.min():g}, {k.max():g}], "
                f"Omega <= {self.omega_max:g}")

    def header_lines(self) -> list[str]:
        k = self.kappa
        out = []
        if self.material is not None:
            out += [f"material: {self.material.describe()}",
                    f"material source: {self.material.source}",
                    f"thickness: d = 2h = {self.thickness_mm:g} mm"]
        else:
            out.append(f"Poisson's ratio: nu = {self.nu:g}")
        out += [f"kappa = k h: {k.size} points from {k.min():g} to {k.max():g} "
                "(h: half the thickness)",
                f"Omega = omega h / c_T: branches up to {self.omega_max:g}"]
        if self.discrete:
            out.append(f"patch: {self.base_patch.geometry_title()}")
            out.append("masses: " + ", ".join(_mass_words(d.patch) for d in self.discrete))
        if self.scheme is not None:
            out.append(f"time integration: Newmark member {self.scheme}, step = {self.courant:g}"
                       " x the critical step of central differences of each mass")
            out += [f"time step of {d.name}: tau = {d.tau:.10g} h / c_T" for d in self.discrete]
            out.append("group velocities: not computed for fully discrete branches (empty)")
        if self.material is not None:
            from dispersion.answers.units import zgv_in_units

            for p in zgv_in_units(self.zgv, self.material, self.thickness_mm):
                out.append(f"ZGV {p['mode']}: f = {p['f [kHz]']:.10g} kHz, fd = "
                           f"{p['fd [MHz mm]']:.10g} MHz mm, c_p = {p['c_p [m/s]']:.10g} m/s")
        out.append("source: exact (Rayleigh-Lamb) or the mass rule of the discrete patch; "
                   "symmetry: S, A or mixed (the mass breaks the mirror)")
        return out

    def columns(self) -> tuple[str, ...]:
        cols = ("kappa", "Omega", "branch", "symmetry", "source", "c_p/c_T", "c_g/c_T")
        if self.material is not None:
            cols += ("f [kHz]", "fd [MHz mm]", "c_p [m/s]", "c_g [m/s]", "wavelength [mm]")
        return cols

    def rows(self) -> list[dict]:
        rows = self._rows(self.exact.omega, self.velocities.group, self.exact.symmetry,
                          "exact", self.nu)
        for d in self.discrete:
            rows += self._rows(d.branches.omega, d.branches.group or {},
                               d.branches.symmetry.get, d.name, self.nu)
        return rows

    def _rows(self, omega, group, symmetry, source, nu) -> list[dict]:
        import numpy as np

        from dispersion.continuum.velocities import phase_velocity

        kappa = self.kappa
        phys = None
        if self.material is not None:
            from dispersion.answers.units import physical_branches

            phys = physical_branches(kappa, omega, group, self.material, self.thickness_mm,
                                     nu=nu)
        out = []
        for label, om in omega.items():
            cp = phase_velocity(kappa, om)
            g = np.asarray(group.get(label, np.full(kappa.shape, np.nan)), dtype=float)
            for i in np.flatnonzero(np.isfinite(om) & (om <= self.omega_max)):
                row = {"kappa": float(kappa[i]), "Omega": float(om[i]), "branch": label,
                       "symmetry": symmetry(label), "source": source,
                       "c_p/c_T": float(cp[i]), "c_g/c_T": float(g[i])}
                if phys is not None:
                    row.update({"f [kHz]": float(phys.frequency[label][i]),
                                "fd [MHz mm]": float(phys.fd[label][i]),
                                "c_p [m/s]": float(phys.phase[label][i]),
                                "c_g [m/s]": float(phys.group[label][i]),
                                "wavelength [mm]": float(phys.wavelength[i])})
                out.append(row)
        return out

    def json_extra(self) -> dict:
        return {"zgv": [{"mode": p.label, "kappa": p.kappa, "Omega": p.omega}
                        for p in self.zgv]}

    # ------------------------------------------------------------------ figure data

    def physical(self):
        """The exact branches in units (:class:`dispersion.answers.units.PhysicalBranches`)."""
        from dispersion.answers.units import physical_branches

        return physical_branches(self.kappa, self.exact.omega, self.velocities.group,
                                 self.material, self.thickness_mm)

    def physical_discrete(self) -> dict:
        """Per discrete set, its branches in units (``name -> PhysicalBranches``)."""
        from dispersion.answers.units import physical_branches

        return {d.name: physical_branches(self.kappa, d.branches.omega, d.branches.group,
                                          self.material, self.thickness_mm, nu=self.nu)
                for d in self.discrete}

    def cutoffs_khz(self) -> dict[str, float]:
        """Cut-off frequencies (kHz) of the exact S and A modes up to ``omega_max``."""
        from dispersion.continuum.rayleigh_lamb import cutoff_frequencies
        from dispersion.answers.units import frequency_khz

        out = {}
        for kind in ("S", "A"):
            for j, (w, _) in enumerate(cutoff_frequencies(kind, self.nu, self.omega_max)):
                if w > 0:
                    out[f"{kind}{j}"] = float(frequency_khz(w, self.material, self.thickness_mm))
        return out


def _mass_words(patch) -> str:
    text = patch.mass_name
    if patch.singular:
        text += (f" (weights {patch.weights_dict})" if patch.weights is not None
                 else f" (contact {patch.contact}, gamma_s = {patch.gamma_s})")
    return text


def _resolve_nu(nu, material):
    from dispersion.errors import check_nu

    if material is not None:
        if nu is not None and float(nu) != material.nu:
            raise InputError(f"nu must not be given with a material (nu = {material.nu:.6g} "
                             f"follows from its c_L and c_T), got {nu}")
        return material.nu
    return float(check_nu(defaults.NU_FLOAT if nu is None else nu))


def _check_scheme(scheme, courant, masses, patch):
    if scheme is None:
        if courant is not None:
            raise InputError("courant applies with a scheme only")
        return
    from dispersion.time_stepping.fully_discrete import time_scheme

    explicit = time_scheme(scheme).explicit
    if not masses:
        raise InputError("scheme applies to the discrete branches (not to the exact ones)")
    if patch.model != "bloch":
        raise InputError("scheme needs the Bloch model (the x-exact model has no largest "
                         "frequency, hence no critical step)")
    limit = 1.0 if explicit else COURANT_MAX
    if courant is None or isinstance(courant, bool) or not (
            math.isfinite(float(courant)) and 0 < float(courant) <= limit):
        raise InputError(f"courant (the step over the critical step) must be in (0, "
                         f"{limit:g}] for scheme {scheme}, got {courant}")


def branch_table(*, mass=None, exact: bool | None = None, masses=None,
                 exact_only: bool | None = None, patch=None, nu=None,
                 material=None, thickness_mm: float | None = None,
                 kappa_min: float = KAPPA_MIN, kappa_max: float = KAPPA_MAX,
                 count: int = COUNT, omega_max: float = OMEGA_MAX, scheme: str | None = None,
                 courant: float | None = None, paired: bool = False,
                 progress=None) -> BranchTable:
    """Exact and discrete branches on a kappa grid (see the module docstring).

    The keywords are the options of ``dispersion branches`` (``--mass`` is ``mass``,
    ``--exact`` is ``exact``, ``--kappa-max`` is ``kappa_max``, ...); ``masses`` and
    ``exact_only`` are the older names of ``mass`` and ``exact`` and keep working.

    Parameters
    ----------
    mass : str, MassRule or a sequence of them, optional
        Mass rule(s) of the discrete patch, names of
        :data:`~dispersion.mass_rules.mass_rule.RULE_NAMES` or rules (default
        :data:`DEFAULT_MASSES`; none with ``exact``). One name is one rule; an empty
        sequence is refused (``exact=True`` asks for the exact branches alone).
    exact : bool
        The exact Rayleigh-Lamb branches alone (default False).
    masses, exact_only :
        The same as ``mass`` and ``exact`` (give one name of each pair, not both).
    patch : Patch, optional
        The discrete patch (p, n, model, r, contact, gamma_s); its mass is replaced by each of
        ``masses``. Default: the toolkit's (:mod:`dispersion.defaults`).
    nu : float, optional
        Poisson's ratio (default 0.3); a material fixes it instead.
    material, thickness_mm : Material or str, float, optional
        A material (or its name in :data:`~dispersion.materials.materials.MATERIALS`) and the
        plate thickness d = 2h in mm, given together: rows in physical units and the ZGV
        points.
    kappa_min, kappa_max : float
        The kappa grid :math:`\\kappa = k h` (h half the thickness, dimensionless) from
        ``kappa_min`` >= 0 to ``kappa_max`` > ``kappa_min`` (default 0 to :data:`KAPPA_MAX`).
    count : int
        Points of the uniform kappa grid, in [2, :data:`MAX_COUNT`] (default :data:`COUNT`);
        discrete branches also within the work bound of
        :func:`dispersion.budget.check_discrete_branches`.
    omega_max : float
        Largest :math:`\\Omega = \\omega h / c_T` drawn, in (0, :data:`MAX_OMEGA`]
        (default :data:`OMEGA_MAX`).
    scheme, courant : str, float, optional
        Fully discrete branches: a Newmark member
        (:data:`~dispersion.time_stepping.time_integration.NEWMARK_MEMBERS`) at ``courant`` times each
        mass's critical step of central differences (Bloch model only).
    paired : bool
        Also pair each exact branch with the discrete mode of the same shape and keep the
        signed errors (the figure's error panel).
    progress : callable, optional
        Called with the number of kappa points done (a progress bar's ``update``).

    Returns
    -------
    BranchTable
        Rows, every format (``to_text``, ``to_csv``, ``to_json``, ``to_dict``) and
        ``failures``; :func:`dispersion.figure` draws it.

    Raises
    ------
    InputError
        A value outside its range, or a request over the work bounds (before any work).

    >>> branch_table(mass="lumped", count=3, kappa_max=1.0, omega_max=1.0).title()
    'Rayleigh-Lamb and discrete branches of the Bloch r = b/h = 2, p = 2, n = 3 patch, nu = 0.3, 3 kappa in [0, 1], Omega <= 1'
    """
    masses = _one_of("mass", mass, "masses", masses)
    exact_only = bool(_one_of("exact", exact, "exact_only", exact_only))
    if isinstance(masses, str) or hasattr(masses, "build"):  # one rule, not its letters
        masses = (masses,)
    from dispersion.symbolic.patch import Patch
    from dispersion.continuum.exact_branches import check_samples, trace_branches
    from dispersion.continuum.velocities import exact_velocities

    if isinstance(material, str):
        from dispersion.materials.materials import material as by_name

        material = by_name(material)
    if (material is None) != (thickness_mm is None):
        raise InputError("a material and thickness_mm (d in mm) go together: units need both")
    if thickness_mm is not None:
        from dispersion.errors import check_positive

        thickness_mm = float(check_positive("thickness_mm", thickness_mm))
    nu = _resolve_nu(nu, material)
    kappa = kappa_grid(kappa_min, kappa_max, count)
    if isinstance(omega_max, bool) or not (isinstance(omega_max, (int, float))
                                           and 0 < omega_max <= MAX_OMEGA):
        raise InputError(f"omega_max must be in (0, {MAX_OMEGA:g}], got {omega_max!r}")
    check_samples(count, omega_max, what="count * (omega_max / 0.05 + 1)")
    if exact_only:
        if masses:
            raise InputError("mass does not apply to the exact branches alone (exact=True)")
        masses = ()
    else:
        masses = tuple(DEFAULT_MASSES if masses is None else masses)
        if not masses:
            raise InputError("mass must name at least one mass rule (exact=True asks for the "
                             "exact branches alone), got an empty sequence")
    base = Patch() if patch is None else patch
    if not isinstance(base, Patch):
        raise InputError(f"patch must be a Patch (dispersion.symbolic.patch), got "
                         f"{type(base).__name__}")
    if masses:
        if base.symbolic_r:
            raise InputError("r must be a number > 0 for numeric branches, got the symbol r")
        check_discrete_branches(count, masses, base.p, base.n)
    _check_scheme(scheme, courant, masses, base)
    exact = trace_branches(nu, kappa, omega_max, progress=progress)
    velocities = exact_velocities(exact)
    sets = [_discrete(base.replace(mass=m), nu, kappa, exact, scheme, courant, paired, progress)
            for m in masses]
    zgv = ()
    if material is not None:
        from dispersion.continuum.frequency import zgv_points_below

        zgv = tuple(p for p in zgv_points_below(nu, omega_max) if p.kappa <= kappa.max())
    failures = [f"exact {kind} branches at kappa = {k:.6g}: {why}"
                for kind, k, why in exact.failures]
    failures += [f"exact {label} group velocity at kappa = {k:.6g}: {why}"
                 for label, k, why in velocities.uncertain]
    failures += [f"discrete {d.name} {what} at kappa = {k:.6g}: {why}"
                 for d in sets for what, k, why in d.branches.failures]
    return BranchTable(nu, kappa, float(omega_max), exact, velocities, tuple(sets),
                       base if masses else None, material, thickness_mm, scheme,
                       None if scheme is None else float(courant), zgv, tuple(failures))


def _one_of(name: str, value, old: str, old_value):
    """The value of a keyword given under its name or its older name (not both)."""
    if value is not None and old_value is not None:
        raise InputError(f"give {name} or its older name {old}, not both")
    return value if value is not None else old_value


def _discrete(patch, nu, kappa, exact, scheme, courant, paired, progress) -> DiscreteSet:
    from dispersion.symbolic.plate import plate_patch
    from dispersion.discretization.discrete_branches import discrete_branches

    plate = plate_patch(patch)
    d = discrete_branches(plate, nu, kappa, progress=progress, group=True)  # fully discrete: by the chain rule
    name = _name(patch.mass)
    if scheme is not None:
        from dispersion.time_stepping.fully_discrete import fully_discrete_branches
        from dispersion.time_stepping.timestep import patch_omega_max

        tau = courant * 2 / patch_omega_max(plate, nu)[0]
        return DiscreteSet(f"{name} {scheme} C={courant:g}", patch,
                           fully_discrete_branches(d, tau, scheme), tau)
    errors, partners = _paired_errors(plate, nu, kappa, exact, d) if paired else (None, None)
    return DiscreteSet(name, patch, d, None, errors, partners)


def _paired_errors(plate, nu, kappa, exact, d) -> tuple[dict, dict]:
    """Signed error of each exact branch against the discrete mode of the same shape, on the
    whole grid (NaN beyond the first Brillouin zone, where no exact partner exists), and that
    partner's place at each kappa (-1: none)."""
    import numpy as np

    from dispersion.continuum.exact_branches import ExactBranches
    from dispersion.discretization.discrete_mode_shapes import pair_by_shape

    inside = kappa <= (d.zone_edge if d.zone_edge is not None else np.inf)
    sub = ExactBranches(kappa[inside], {lab: w[inside] for lab, w in exact.omega.items()},
                        exact.nu, exact.omega_max)
    pad = int(np.count_nonzero(~inside))
    pb = pair_by_shape(plate, nu, sub)
    return ({lab: np.concatenate([e, np.full(pad, np.nan)])
             for lab, e in pb.relative_error(sub).items()},
            {lab: np.concatenate([c, np.full(pad, -1)]) for lab, c in pb.partner.items()})
