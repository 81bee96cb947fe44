"""``dispersion ring``: the ring benchmark (paper sec. 3) with one mass variant.

Examples::

    dispersion ring --mass singular --t-end 40 --format json
    dispersion ring --mass lumped --level 1 --dt 0.025 --t-end 30 --out results/ring
"""
from __future__ import annotations

import argparse
import sys
from dataclasses import replace

from dispersion.contact.scenario import MAX_STEPS, Scenario
from dispersion.errors import InputError
from dispersion.cli.options import choice, integer, lazy_help, number

DEFAULT = Scenario()

#: Scenario fields the CLI exposes: option name -> (field, unit).
_FIELDS = {
    "r-inner": ("r_inner", "m"), "r-outer": ("r_outer", "m"), "theta0": ("theta0_deg", "deg"),
    "gap": ("gap", "m"), "rho": ("rho", "kg/m^3"), "nu": ("nu", "dimensionless"), "v0": ("v0", "m/s"),
    "v0-over-ct": ("v0_over_cT", "dimensionless"), "dt": ("dt", "s"), "t-end": ("t_end", "s"),
    "xi-elements": ("n_xi_elements", "count"), "eta-elements": ("n_eta_elements", "count"),
    "gamma-s": ("gamma_s", "dimensionless"),
}

#: What each option means, in the user's words (its help text; unit and default are added).
_MEANING = {
    "r-inner": "inner radius of the quarter ring", "r-outer": "outer radius of the quarter ring",
    "theta0": "where the quarter arc starts (angle from the x axis; 180: lands on its middle)",
    "gap": "initial gap between the ring and the plane", "rho": "density",
    "nu": "Poisson's ratio", "v0": "initial speed towards the plane",
    "v0-over-ct": "initial speed over the shear wave speed c_T (sets Young's modulus E)",
    "dt": "time step", "t-end": "end time",
    "xi-elements": "elements along the arc", "eta-elements": "elements through the thickness",
    "gamma-s": "share of a contact shape function sent to the second neighbour",
}

#: Files ``--out`` writes (its help text and the test of it use this one list).
OUT_FILES = {
    "summary.json": "inputs and results of the run (energy change, penetration, events)",
    "result.json": "the whole run: scene, summary and every time step's histories "
                   "(about 150 KB for the default scene)",
    "history.csv": "time histories with units, after # lines with the inputs",
    "figure.png": "contact force and total energy change (%) against time",
}


#: Mesh refinement levels ``--level`` accepts: level 4 is the finest mesh a scenario allows
#: (:data:`~dispersion.contact.scenario.MAX_ELEMENTS`).
LEVELS = (0, 4)


def level(text: str) -> int:
    """argparse ``type`` of ``--level``: an integer in :data:`LEVELS`, stated on failure.

    >>> level("abc")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: level must be an integer in [0, 4], got 'abc'
    """
    return integer("level", *LEVELS)(text)


def progress_default(flag) -> bool:
    return sys.stderr.isatty() if flag is None else flag


def _rules():
    from dispersion.symbolic.mass_rule import RULE_NAMES

    return RULE_NAMES


def _schemes():
    from dispersion.contact.newmark_scheme import CONTACT_SCHEMES

    return CONTACT_SCHEMES


def register(sub) -> None:
    p = sub.add_parser("ring", help="ring bouncing on a rigid plane (paper Figure 4)",
                       description="Quarter ring (one quadratic NURBS patch) bouncing on a "
                                   "rigid frictionless plane; reconstructed scenario (see "
                                   "dispersion.contact.scenario). Every default below is the "
                                   "default scene. " + _stability_note())
    p.add_argument("--mass", type=choice("--mass", _rules), default="singular", metavar="RULE",
                   help=lazy_help("mass rule, one of {names} (default: singular)", _rules))
    p.add_argument("--scheme", type=choice("--scheme", _schemes), default="kane", metavar="NAME",
                   help=lazy_help("time integrator, one of {names}: contact-modified Newmark "
                                  "(Kane), standard Newmark, explicit central differences "
                                  "(default: kane)", _schemes))
    p.add_argument("--level", type=level, default=0,
                   help="mesh refinement level: elements x 2^level in both directions "
                        "(default: 0)")
    for opt, (name, unit) in _FIELDS.items():
        kind = int if name.startswith("n_") else float
        extra = " (singular masses only)" if name == "gamma_s" else ""
        unit_text = "" if unit in ("dimensionless", "count") else f" [{unit}]"
        p.add_argument(f"--{opt}", type=number(opt, kind), default=None,
                       help=f"{_MEANING[opt]}{unit_text}, default {getattr(DEFAULT, name):g}"
                            f"{extra}")
    p.add_argument("--out", metavar="DIR",
                   help="folder (new, or written by dispersion) to write: " + "; ".join(
                       f"{name}: {what}" for name, what in OUT_FILES.items()).replace("%", "%%"))
    p.add_argument("--format", choices=("text", "json", "csv"), default="text",
                   help="stdout: one-line summary, JSON summary, or CSV history (default: text)")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="tqdm progress bar on stderr (default: on a terminal)")
    p.epilog = f"At most {MAX_STEPS} steps (t_end / dt) per run."
    p.set_defaults(func=run)


def scenario_from(args) -> Scenario:
    """The scenario the options describe (refines the mesh after setting element counts)."""
    if not LEVELS[0] <= args.level <= LEVELS[1]:
        raise InputError(f"level must be an integer in [{LEVELS[0]}, {LEVELS[1]}], "
                         f"got {args.level}")
    if args.gamma_s is not None and not args.mass.startswith("singular"):
        raise InputError(f"gamma-s applies to the singular masses only, not mass {args.mass!r}")
    changes = {name: getattr(args, opt.replace("-", "_")) for opt, (name, _) in _FIELDS.items()
               if getattr(args, opt.replace("-", "_")) is not None}
    return replace(DEFAULT, **changes).with_level(args.level)


def _stability_note() -> str:
    from dispersion.contact.energy_balance import STABILITY_NOTE

    return STABILITY_NOTE


def run(args) -> int:
    from dispersion.contact.simulate import simulate_ring
    from dispersion.io import check_output_dir
    from dispersion.results import dumps

    out = None if args.out is None else check_output_dir(args.out, option="--out")
    if out is not None:
        from dispersion.plotting import require_matplotlib

        require_matplotlib("ring --out (its figure.png)")
    sc = scenario_from(args)
    bar = None
    if progress_default(args.progress):
        from tqdm import tqdm

        bar = tqdm(total=sc.n_steps, desc=f"ring {args.mass}", unit="step", file=sys.stderr)
    try:
        res = simulate_ring(sc, args.mass, args.scheme,
                            progress=bar.update if bar is not None else None)
    finally:
        if bar is not None:
            bar.close()
    if res.summary.get("energy_flag"):
        print(f"warning: ring ({args.mass} mass, {args.scheme}): {res.summary['energy_flag']}; "
              "the figures of this run are not a result", file=sys.stderr)
    if out is not None:
        import io

        from dispersion.io import write_files
        from dispersion.plotting.ring import plot_contact_energy

        png = io.BytesIO()
        plot_contact_energy(res.to_dict()).savefig(png, format="png", dpi=120)
        files = {"summary.json": dumps(res.summary),  # one unit: all new or all old
                 "result.json": dumps(res.to_dict(), indent=None),
                 "history.csv": res.csv_text(), "figure.png": png.getvalue()}
        write_files(out, files, option="--out")
    if args.format == "json":
        sys.stdout.write(dumps(res.summary))
    elif args.format == "csv":
        sys.stdout.write(res.csv_text())
    else:
        s = res.summary
        print(f"ring ({s['mass']} mass, {s['scheme']}): energy change "
              f"{s['energy_change_percent']:+.3f} %, max penetration "
              f"{s['max_penetration_greville']:.2e} m at the Greville points, "
              f"{s['max_penetration']:.2e} m between them, {s['contact_events']} contact "
              f"events, rotation {s['final_rotation_deg']:.1f} deg"
              + (" [UNSTABLE: energy grows; not a result]" if s.get("energy_flag") else ""))
    return 0
