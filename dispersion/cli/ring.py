"""``dispersion ring``: :func:`dispersion.contact.simulate.simulate_ring` on the command line
(the ring benchmark of the paper's sec. 3, one mass rule and scheme), e.g.
``dispersion ring --mass lumped --level 1 --dt 0.025 --t-end 30 --out results/ring``.
"""
from __future__ import annotations

import argparse
from dataclasses import replace

from dispersion.cli.options import choice, integer, lazy_help, real
from dispersion.contact.scenario import MAX_STEPS, Scenario

DEFAULT = Scenario()

#: Scenario fields the CLI exposes: option -> (field, unit, meaning); the help adds the
#: default from the scene.
_FIELDS = {
    "r-inner": ("r_inner", "m", "inner radius of the quarter ring"),
    "r-outer": ("r_outer", "m", "outer radius of the quarter ring"),
    "theta0": ("theta0_deg", "deg", "where the quarter arc starts (angle from the x axis; "
                                    "180: lands on its middle)"),
    "gap": ("gap", "m", "initial gap between the ring and the plane"),
    "rho": ("rho", "kg/m^3", "density"), "nu": ("nu", "", "Poisson's ratio"),
    "v0": ("v0", "m/s", "initial speed towards the plane"),
    "v0-over-ct": ("v0_over_cT", "", "initial speed over the shear wave speed c_T (sets "
                                     "Young's modulus E)"),
    "dt": ("dt", "s", "time step"), "t-end": ("t_end", "s", "end time"),
    "xi-elements": ("n_xi_elements", "", "elements along the arc"),
    "eta-elements": ("n_eta_elements", "", "elements through the thickness"),
    "gamma-s": ("gamma_s", "", "share of a contact shape function sent to the second "
                               "neighbour (singular mass rules only)"),
}

#: Files ``--out`` writes (its help text and the test of it use this one list).
OUT_FILES = {
    "summary.json": "inputs and results of the run (energy change, penetration, events)",
    "result.json": "the whole run: scene, summary and every time step's histories "
                   "(about 150 KB for the default scene)",
    "history.csv": "time histories with units, after # lines with the inputs",
    "figure.png": "contact force and total energy change (%) against time",
}

#: Mesh refinement levels ``--level`` accepts: level 4 is the finest mesh a scenario allows.
LEVELS = (0, 4)


def _rules():
    from dispersion.mass_rules.mass_rule import RULE_NAMES

    return RULE_NAMES


def _schemes():
    from dispersion.contact.newmark_scheme import CONTACT_SCHEMES

    return CONTACT_SCHEMES


def _stability_note() -> str:
    from dispersion.contact.energy_balance import STABILITY_NOTE

    return STABILITY_NOTE


def register(sub) -> None:
    from dispersion.cli.outputs import add_outputs

    p = sub.add_parser("ring", help="ring bouncing on a rigid plane (paper Figure 4)",
                       description="Quarter ring (one quadratic NURBS patch) bouncing on a "
                                   "rigid frictionless plane; reconstructed scenario (see "
                                   "dispersion.contact.scenario). Every default below is the "
                                   "default scene. " + _stability_note(),
                       epilog=f"At most {MAX_STEPS} steps (t_end / dt) per run.")
    p.add_argument("--mass", type=choice("--mass", _rules), default="singular", metavar="RULE",
                   help=lazy_help("mass rule, one of {names} (default: singular)", _rules))
    p.add_argument("--scheme", type=choice("--scheme", _schemes), default="kane", metavar="NAME",
                   help=lazy_help("time integrator, one of {names}: contact-modified Newmark "
                                  "(Kane), standard Newmark, explicit central differences "
                                  "(default: kane)", _schemes))
    p.add_argument("--level", type=integer("--level", *LEVELS), default=0,
                   help="mesh refinement level: elements x 2^level in both directions, in "
                        f"[{LEVELS[0]}, {LEVELS[1]}] (default: 0)")
    for opt, (name, unit, meaning) in _FIELDS.items():
        kind = integer(f"--{opt}", 1) if name.startswith("n_") else real(f"--{opt}")
        unit_text = f" [{unit}]" if unit else ""
        p.add_argument(f"--{opt}", type=kind, default=None,
                       help=f"{meaning}{unit_text} (default: {getattr(DEFAULT, name):g})")
    p.add_argument("--out", metavar="DIR",
                   help="folder (new, or written by dispersion) to write: " + "; ".join(
                       f"{name}: {what}" for name, what in OUT_FILES.items()).replace("%", "%%"))
    add_outputs(p, csv=False, json=False, piped="text")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress bar on stderr (default: on a terminal)")
    p.set_defaults(func=run)


def scenario_from(args) -> Scenario:
    """The scenario the options describe (refines the mesh after setting element counts)."""
    from dispersion.cli.options import check_applies
    from dispersion.mass_rules.mass_rule import get_rule

    check_applies(args, [("--gamma-s", lambda a: get_rule(a.mass).redistributes,
                          "to a singular mass rule")])
    changes = {name: getattr(args, opt.replace("-", "_")) for opt, (name, *_) in _FIELDS.items()
               if getattr(args, opt.replace("-", "_")) is not None}
    return replace(DEFAULT, **changes).with_level(args.level)


def run(args) -> int:
    from dispersion.cli.outputs import progress_bar, warn_failures, write_outputs
    from dispersion.contact.simulate import simulate_ring
    from dispersion.io import check_output_dir

    out = None if args.out is None else check_output_dir(args.out, option="--out")
    if out is not None:
        from dispersion.plotting import require_matplotlib

        require_matplotlib("ring --out (its figure.png)")
    sc = scenario_from(args)
    bar = progress_bar(args.progress, f"ring {args.mass}", "step", sc.n_steps)
    try:
        res = simulate_ring(sc, args.mass, args.scheme,
                            progress=None if bar is None else bar.update)
    finally:
        if bar is not None:
            bar.close()
    warn_failures(res)
    if out is not None:
        import io

        from dispersion.io import write_files
        from dispersion.plotting.ring import plot_contact_energy
        from dispersion.results import dumps

        png = io.BytesIO()
        plot_contact_energy(res.to_dict()).savefig(png, format="png", dpi=120)
        files = {"summary.json": dumps(res.summary),  # one unit: all new or all old
                 "result.json": dumps(res.to_dict(), indent=None),
                 "history.csv": res.to_csv(), "figure.png": png.getvalue()}
        write_files(out, files, option="--out")
    write_outputs(args, res)
    return 0
