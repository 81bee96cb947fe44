"""``dispersion branches``: discrete and exact Rayleigh-Lamb branches with velocities and units.

With ``--frequency``/``--fd`` the frequency is the input axis instead of kappa: every
propagating S, A and SH mode at each frequency (:mod:`dispersion.cli.frequency`).

Rows ``kappa, Omega, branch, symmetry, source, c_p/c_T, c_g/c_T`` (dimensionless: kappa = kh,
Omega = omega h / c_T) and, with a material and a thickness, ``f [kHz], fd [MHz mm],
c_p [m/s], c_g [m/s], wavelength [mm]``. ``--scheme central --courant 0.9`` gives the fully
discrete branches of the discrete patch (:mod:`dispersion.waves.fully_discrete`: each mass
integrated in time at ``courant`` times its own central-difference critical step; group
velocities are then left empty). ``--csv FILE`` / ``--figure FILE`` write files
(``-``: stdout); without them the rows go to stdout as ``--format`` says. Every CSV starts
with ``#`` lines naming its inputs and the package version; JSON carries them as ``inputs``.
"""
from __future__ import annotations

import argparse
import io
import math
import os
import sys
from typing import TYPE_CHECKING

from dispersion import defaults
from dispersion.defaults import CONTACT_SETS, MASS_VARIANTS, MODELS, N_MAX, P_MAX, R_RANGE
from dispersion.errors import InputError
from dispersion.io import check_output_file, unit_target, write_bytes, write_unit
from dispersion.cli import frequency as _frequency
from dispersion.cli.options import integer, number, real

if TYPE_CHECKING:  # numpy and the tracer are imported where used: --help stays light
    import numpy as np

#: Up-front bounds (issue 11); the exact tracer's scan is bounded by
#: :data:`dispersion.waves.exact_branches.MAX_SAMPLES` (count * (omega-max / 0.05 + 1)).
MAX_COUNT = 200_000
MAX_OMEGA = 200.0
#: Discrete branches: the largest n, and count * (mass variants) * n^3 <= MAX_DISCRETE_WORK.
#: Rule: the default run (two masses, 400 kappa points) at the largest n in about a minute and a
#: half. Measured on this 2-core machine, 400 kappa points, consistent + singular: n = 10 in
#: 3.4 s, n = 20 in 48 s, n = 30 in 180 s (grows like n^3); n = 3 with 200000 points: ~1e7.
#: Work bound of the numeric branches: 400 kappa of two masses at n = 24 (about a minute).
MAX_DISCRETE_WORK = 2 * 400 * 24**3


def register(sub) -> None:
    p = sub.add_parser(
        "branches", help="dispersion branches: discrete patch and Rayleigh-Lamb",
        description="All discrete branches of the plate patch and the exact Rayleigh-Lamb "
                    "branches below Omega_max on a kappa grid (paper Figure 2), with phase "
                    "and group velocity, optionally in physical units.")
    p.add_argument("--mass", choices=MASS_VARIANTS, action="append",
                   help="mass variant (repeat for several; default: consistent and singular)")
    p.add_argument("--mass-rule", action="append", default=[], metavar="FILE",
                   help="a user mass rule: TOML table of redistribution weights (repeatable)")
    p.add_argument("--contact", choices=CONTACT_SETS, default=None,
                   help=f"contact set of a singular mass (default: {defaults.CONTACT})")
    p.add_argument("--gamma-s", type=real("gamma_s", 0, 1), default=None,
                   help="share of a contact shape function sent to the second neighbour, "
                        f"singular masses only (default: {defaults.text('GAMMA_S')})")
    p.add_argument("--model", choices=MODELS, default=None,
                   help=f"patch model along x (default: {defaults.MODEL})")
    p.add_argument("--r", type=real("r", *R_RANGE), default=None,
                   help=f"aspect ratio b/h of the Bloch model, dimensionless, in [1/1000, "
                        f"1000] (default: {defaults.R}; Figure 2's caption is 1/2)")
    p.add_argument("--p", type=integer("degree p", 1, P_MAX), default=defaults.P,
                   help=f"degree through the thickness, in [1, {P_MAX}] "
                        f"(default: {defaults.P})")
    p.add_argument("--n", type=integer("control points n", 2, N_MAX), default=defaults.N,
                   help=f"control points through the thickness, in [p + 1, {N_MAX}], and "
                        f"count * (mass variants) * n^3 <= {MAX_DISCRETE_WORK} "
                        f"(default: {defaults.N})")
    p.add_argument("--nu", type=real("nu", -1, 0.5, lo_open=True, hi_open=True), default=None,
                   help=f"Poisson's ratio (default: {defaults.NU_FLOAT}, or the material's)")
    p.add_argument("--kappa-min", type=real("kappa-min", 0), default=None,
                   help="smallest kappa = kh, dimensionless (default: 0)")
    p.add_argument("--kappa-max", type=real("kappa-max", 0), default=None,
                   help="largest kappa = kh, dimensionless (default: 8)")
    p.add_argument("--count", type=integer("count", 2, MAX_COUNT), default=None,
                   help=f"number of kappa points, in [2, {MAX_COUNT}] (default: 400)")
    p.add_argument("--omega-max", type=real("omega-max", 0, MAX_OMEGA, lo_open=True),
                   default=None,
                   help=f"largest Omega = omega h / c_T, in (0, {MAX_OMEGA:g}] (default: 8)")
    p.add_argument("--material", choices=sorted(_materials()),
                   help="material for physical units (bulk speeds and density of the CRC "
                        "handbook row in dispersion.waves.materials)")
    p.add_argument("--cl", type=real("cl"), help="longitudinal speed c_L in m/s")
    p.add_argument("--ct", type=real("ct"), help="shear speed c_T in m/s")
    p.add_argument("--thickness", type=real("thickness"),
                   help="plate thickness d = 2h in mm (with a material: physical columns)")
    p.add_argument("--scheme", choices=_schemes(), default=None,
                   help="time integrator for fully discrete branches (default: none, "
                        "semi-discrete); Bloch model only")
    p.add_argument("--courant", type=number("courant"), default=None,
                   help="time step as a fraction of each mass's central-difference critical "
                        "step, in (0, 10] (with --scheme; explicit schemes need <= 1)")
    p.add_argument("--exact", action="store_true", help="Rayleigh-Lamb branches only")
    p.add_argument("--exact-only", dest="exact", action="store_true", help=argparse.SUPPRESS)
    p.add_argument("--format", choices=("text", "csv", "json"), default=None,
                   help="what goes to stdout when no --csv/--figure is given (default: csv); "
                        "an error with --csv or --figure")
    p.add_argument("--csv", help="write the rows as CSV to FILE ('-': stdout)")
    p.add_argument("--figure", help="write the figure to FILE (.png, .pdf or .svg)")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="tqdm progress bar on stderr (default: on a terminal)")
    _frequency.add_arguments(p)
    p.set_defaults(func=run)


def _schemes():
    return defaults.TIME_SCHEMES


def _materials():
    from dispersion.waves.materials import MATERIALS

    return MATERIALS


def kappa_grid(kmin: float, kmax: float, count: int) -> np.ndarray:
    """Checked uniform grid: finite, 0 <= kmin < kmax, 2 <= count <= MAX_COUNT."""
    if not (math.isfinite(kmin) and math.isfinite(kmax)):
        raise InputError(f"kappa range must be finite, got [{kmin}, {kmax}]")
    if kmin < 0 or kmax <= kmin:
        raise InputError(f"kappa range must satisfy 0 <= kappa-min < kappa-max, got "
                         f"[{kmin}, {kmax}]")
    if isinstance(count, bool) or not 2 <= count <= MAX_COUNT:
        raise InputError(f"count must be an integer in [2, {MAX_COUNT}], got {count}")
    import numpy as np

    return np.linspace(kmin, kmax, count)


def _material(args):
    from dispersion.cli.options import material_from_args

    mat = material_from_args(args)
    if mat is not None and args.thickness is None:
        raise InputError("a material needs --thickness (plate thickness d = 2h in mm)")
    if mat is None and args.thickness is not None:
        raise InputError("--thickness needs a material (--material or --cl/--ct)")
    return mat


def _settings(args) -> dict:
    """Validate every option before any work; return the resolved inputs."""
    if args.format is not None and (args.csv or args.figure):
        raise InputError("--format says what goes to stdout and does not apply with --csv "
                         "or --figure (they write files; '--csv -' writes CSV to stdout)")
    args.format = args.format or "csv"
    for opt, val in (("--mode-shape", args.mode_shape), ("--json", args.json)):
        if val is not None:
            raise InputError(f"{opt} applies with --frequency/--fd only")
    args.kappa_min = 0.0 if args.kappa_min is None else args.kappa_min
    args.kappa_max = 8.0 if args.kappa_max is None else args.kappa_max
    args.count = 400 if args.count is None else args.count
    args.omega_max = 8.0 if args.omega_max is None else args.omega_max
    if args.exact:
        for opt, val in (("--mass", args.mass), ("--contact", args.contact),
                         ("--gamma-s", args.gamma_s), ("--r", args.r), ("--model", args.model)):
            if val is not None:
                raise InputError(f"{opt} does not apply with --exact (no discrete patch)")
    if args.exact and args.mass_rule:
        raise InputError("--mass-rule does not apply with --exact (no discrete patch)")
    if args.mass_rule:
        from dispersion.symbolic.mass_rule import rule_from_toml

        rules = [rule_from_toml(path) for path in args.mass_rule]
    else:
        rules = []
    masses = [] if args.exact else (args.mass or ([] if rules else ["consistent", "singular"]))
    masses = masses + rules
    if masses and not any(_redistributes(m) for m in masses):
        for opt, val in (("--contact", args.contact), ("--gamma-s", args.gamma_s)):
            if val is not None:
                raise InputError(f"{opt} applies to singular masses only")
    args.model = args.model or defaults.MODEL
    if args.model != "bloch" and args.r is not None:
        raise InputError("--r applies to the bloch model only")
    base = None
    if masses:
        from dispersion.symbolic.patch import Patch

        # the one patch of this run (every field but the mass), checked before any work
        base = Patch(args.p, args.n, args.model,
                     defaults.R if args.r is None else args.r, "consistent",
                     args.contact or defaults.CONTACT,
                     defaults.GAMMA_S if args.gamma_s is None else args.gamma_s)
        work = args.count * len(masses) * args.n**3
        if work > MAX_DISCRETE_WORK:
            raise InputError(f"count * (mass variants) * n^3 must be <= {MAX_DISCRETE_WORK} "
                             f"(about a minute and a half), got {work}")
    material = _material(args)
    if args.nu is not None and material is not None and args.youngs_modulus is None:
        raise InputError("--nu does not apply with a material (nu follows from c_L and c_T)")
    nu = material.nu if material is not None else (
        defaults.NU_FLOAT if args.nu is None else args.nu)
    kappa = kappa_grid(args.kappa_min, args.kappa_max, args.count)
    if not (math.isfinite(args.omega_max) and 0 < args.omega_max <= MAX_OMEGA):
        raise InputError(f"omega-max must be in (0, {MAX_OMEGA:g}], got {args.omega_max}")
    from dispersion.waves.exact_branches import check_samples

    check_samples(args.count, args.omega_max, what="count * (omega-max / 0.05 + 1)")
    if args.csv is not None:
        check_output_file(args.csv, option="--csv")
    if args.figure is not None:
        from dispersion.cli.outputs import check_figure

        check_figure(args.figure, "branches")
        if args.csv not in (None, "-") and unit_target(args.csv) is not None and \
                os.path.abspath(unit_target(args.csv)) == os.path.abspath(unit_target(args.figure)
                                                                          or args.figure):
            raise InputError(f"--csv and --figure must name two different files, got "
                             f"{args.csv!r} and {args.figure!r}")
    _check_scheme(args, masses)
    return {
        "nu": nu, "kappa": kappa, "masses": masses, "material": material, "patch": base,
        "r": None if base is None or base.r is None else float(base.r),
        "contact": None if base is None else base.contact,
        "gamma_s": None if base is None else float(base.gamma_s),
    }


def _redistributes(mass) -> bool:
    """True for rules that take the contact set (the singular ones)."""
    from dispersion.symbolic.mass_rule import get_rule

    return get_rule(mass).redistributes


def _name(mass) -> str:
    return getattr(mass, "name", mass)


def _check_scheme(args, masses) -> None:
    if args.scheme is None:
        if args.courant is not None:
            raise InputError("--courant applies with --scheme only")
        return
    if not masses:
        raise InputError("--scheme applies to the discrete branches (not with --exact)")
    if args.model != "bloch":
        raise InputError("--scheme needs --model bloch (the x-exact model has no largest "
                         "frequency, hence no critical step)")
    if args.figure is not None:
        raise InputError("--figure does not draw fully discrete branches yet; use --csv")
    if args.courant is None:
        raise InputError("--scheme needs --courant (the step over the critical step)")
    limit = 1.0 if args.scheme == "central" else 10.0
    if not (math.isfinite(args.courant) and 0 < args.courant <= limit):
        raise InputError(f"courant must be in (0, {limit:g}] for scheme {args.scheme}, "
                         f"got {args.courant}")


def _inputs(args, s) -> dict:
    from dispersion.results import package_versions

    out = {"nu": s["nu"]}
    if s["masses"]:  # the patch's parameters apply only where a patch is computed
        out.update({"model": args.model, "p": args.p, "n": args.n,
                    "masses": [_name(m) for m in s["masses"]]})
    out.update({"kappa": [args.kappa_min, args.kappa_max, args.count],
                "omega_max": args.omega_max,
                "dispersion-iga": package_versions(("dispersion-iga",))["dispersion-iga"]})
    if args.model == "bloch" and s["masses"]:
        out["r"] = s["r"]
    if any(_redistributes(m) for m in s["masses"]):
        out["contact"], out["gamma_s"] = s["contact"], s["gamma_s"]
    if args.scheme is not None:
        out["scheme"], out["courant"] = args.scheme, args.courant
        out["tau"] = s["tau"]
    if s["material"] is not None:
        out["material"] = s["material"].as_dict()
        out["thickness [mm]"] = args.thickness
    return out


def _rows(kappa, omega, group, symmetry, source, material, thickness, omega_max, nu):
    """Row dicts of one branch set (finite Omega <= omega_max) computed at ``nu``."""
    import numpy as np

    from dispersion.waves.units import physical_branches
    from dispersion.waves.velocities import phase_velocity

    phys = (physical_branches(kappa, omega, group, material, thickness, nu=nu)
            if material is not None else None)
    rows = []
    for label, om in omega.items():
        cp = phase_velocity(kappa, om)
        g = group.get(label, np.full(kappa.shape, np.nan))
        for i in np.flatnonzero(np.isfinite(om) & (om <= omega_max)):
            row = {"kappa": float(kappa[i]), "Omega": float(om[i]), "branch": label,
                   "symmetry": symmetry(label), "source": source,
                   "c_p/c_T": float(cp[i]), "c_g/c_T": float(g[i])}
            if phys is not None:
                row.update({"f [kHz]": float(phys.frequency[label][i]),
                            "fd [MHz mm]": float(phys.fd[label][i]),
                            "c_p [m/s]": float(phys.phase[label][i]),
                            "c_g [m/s]": float(phys.group[label][i]),
                            "wavelength [mm]": float(phys.wavelength[i])})
            rows.append(row)
    return rows


def _csv(rows, inputs, failures=()) -> str:
    from dispersion.cli.outputs import EMPTY_NOTE, csv_text

    return csv_text(rows, [f"# {key}: {val}" for key, val in inputs.items()]
                    + [f"# failure: {line}" for line in failures] + [f"# {EMPTY_NOTE}"])


def _text(rows, inputs) -> str:
    lines = [f"# {k}: {v}" for k, v in inputs.items()]
    if rows:
        cols = list(rows[0])
        lines.append("  ".join(f"{c:>14}" for c in cols))
        for row in rows:
            lines.append("  ".join(f"{v:>14.8g}" if isinstance(v, float) else f"{v:>14}"
                                   for v in row.values()))
    return "\n".join(lines) + "\n"


def run(args) -> int:
    import numpy as np

    from dispersion.cli.outputs import emit
    from dispersion.waves.discrete_branches import discrete_branches
    from dispersion.symbolic.plate import plate_patch
    from dispersion.waves.exact_branches import trace_branches
    from dispersion.waves.velocities import exact_velocities

    if _frequency.requested(args):
        return _frequency.run(args)
    s = _settings(args)
    kappa, masses, nu = s["kappa"], s["masses"], s["nu"]
    show = sys.stderr.isatty() if args.progress is None else args.progress
    bar = None
    if show:
        from tqdm import tqdm

        total = 2 * int(np.count_nonzero(kappa > 0)) + kappa.size * len(masses)
        bar = tqdm(total=total, desc="branches", unit="kappa", file=sys.stderr)
    tick = bar.update if bar else None
    exact = trace_branches(nu, kappa, args.omega_max, progress=tick)
    vel = exact_velocities(exact)
    results, patches = [], {}
    for mass in masses:
        patch = plate_patch(s["patch"].replace(mass=mass))
        patches[_name(mass)] = patch
        d = discrete_branches(patch, nu, kappa, progress=tick, group=True)
        if args.scheme is not None:
            from dispersion.waves.fully_discrete import fully_discrete_branches
            from dispersion.waves.timestep import patch_omega_max

            tau = args.courant * 2 / patch_omega_max(patch, nu)[0]
            s.setdefault("tau", {})[_name(mass)] = tau
            d = fully_discrete_branches(d, tau, args.scheme)
            results.append((f"{_name(mass)} {args.scheme} C={args.courant:g}", d))
        else:
            results.append((_name(mass), d))
    if bar:
        bar.close()
    for kind, k, why in exact.failures:
        print(f"warning: exact {kind} branches at kappa={k:.6g}: {why}", file=sys.stderr)
    for label, k, why in vel.uncertain:
        print(f"warning: exact {label} group velocity at kappa={k:.6g}: {why}", file=sys.stderr)
    for mass, d in results:
        for what, k, why in d.failures[:5]:
            print(f"warning: discrete {mass} {what} at kappa={k:.6g}: {why}", file=sys.stderr)
        if len(d.failures) > 5:
            print(f"warning: discrete {mass}: {len(d.failures) - 5} more kappa not certified",
                  file=sys.stderr)
    inputs = _inputs(args, s)
    if s["material"] is not None:  # the practitioner's path: ZGV points in the output
        from dispersion.waves.frequency import zgv_points
        from dispersion.waves.units import zgv_in_units

        points = zgv_in_units(zgv_points(nu, args.omega_max), s["material"], args.thickness)
        for p in points:
            inputs[f"ZGV {p['mode']}"] = (f"f = {p['f [kHz]']:.10g} kHz, fd = "
                                          f"{p['fd [MHz mm]']:.10g} MHz mm, c_p = "
                                          f"{p['c_p [m/s]']:.10g} m/s")
    rows = _rows(kappa, exact.omega, vel.group, lambda lab: lab[0], "exact", s["material"],
                 args.thickness, args.omega_max, nu)
    # every value not certified, in every output format (issue 26): JSON "failures", CSV
    # "# failure:" lines
    failures = [f"exact {kind} branches at kappa={k:.6g}: {why}"
                         for kind, k, why in exact.failures] + \
        [f"exact {label} group velocity at kappa={k:.6g}: {why}" for label, k, why in vel.uncertain] \
        + [f"discrete {mass} {line}" for mass, d in results for line in d.failure_lines()]
    for mass, d in results:
        rows += _rows(kappa, d.omega, d.group or {}, d.symmetry.get, mass, s["material"],
                      args.thickness, args.omega_max, nu)
    if not args.csv and not args.figure:
        if args.format == "csv":
            emit("-", _csv(rows, inputs, failures))
        elif args.format == "text":
            emit("-", _text(rows, inputs))
        else:
            from dispersion.results import dumps, envelope

            env = envelope("branches", {"rows": rows,
                                        "failures": failures,
                                        "velocity_uncertain": [list(u) for u in vel.uncertain]},
                           inputs=inputs)
            emit("-", dumps(env))
    if args.figure and s["material"] is not None:
        fig = _physical_figure(kappa, exact, vel, s["material"], args.thickness, args.omega_max)
    elif args.figure:
        from dispersion.plotting.branches import caption, figure2, plot_exact

        if results:
            from dispersion.studies.branch_study import figure2_data

            data, _ = figure2_data(nu, kappa, args.omega_max, patches, exact=exact,
                                   velocities=vel, discrete=dict(results))
            specs = [pt.spec for pt in patches.values()]
            fig = figure2(data, title=f"nu = {nu:g}, {specs[0].geometry_title()}; "
                                      + ", ".join(sp.mass_title() for sp in specs))
        else:
            fig = plot_exact(kappa, exact.omega, args.omega_max)
            fig.axes[0].set_title(caption(inputs), fontsize="small")
            fig.axes[0].legend(fontsize="small")
    if args.figure:
        figure_bytes = io.BytesIO()
        fig.savefig(figure_bytes, format=args.figure.rsplit(".", 1)[-1].lower(), dpi=150)
    # the CSV and the figure are one unit (io.write_unit): both new, or both old; a stream
    # ('-', a device) is written after the unit
    outputs = ([(args.figure, figure_bytes.getvalue())] if args.figure else []) + (
        [(args.csv, _csv(rows, inputs, failures))] if args.csv else [])
    unit = {unit_target(path): data for path, data in outputs if unit_target(path) is not None}
    if unit:
        write_unit(unit, option="--csv/--figure")
    for path, data in outputs:
        if unit_target(path) is not None:
            continue
        if isinstance(data, str):
            emit(path, data)
        else:
            write_bytes(path, data)
    return 0


def _physical_figure(kappa, exact, vel, material, thickness, omega_max):
    """The exact branches in the practitioner's units (c_p, c_g against fd; k against f),
    ZGV points and cut-offs marked, titled from the result."""
    from dispersion.plotting.lamb import figure_dispersion
    from dispersion.waves.rayleigh_lamb import cutoff_frequencies
    from dispersion.waves.units import frequency_khz, physical_branches, zgv_in_units
    from dispersion.waves.frequency import zgv_points

    phys = physical_branches(kappa, exact.omega, vel.group, material, thickness)
    zgv = [p for p in zgv_points(exact.nu, omega_max) if p.kappa <= kappa.max()]
    cut = {}
    for kind in ("S", "A"):
        for j, (w, _) in enumerate(cutoff_frequencies(kind, exact.nu, omega_max)):
            if w > 0:
                cut[f"{kind}{j}"] = float(frequency_khz(w, material, thickness))
    return figure_dispersion(phys.curves(), phys.title(), zgv_in_units(zgv, material, thickness),
                             cut)
