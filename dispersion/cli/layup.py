"""``dispersion branches --exact --layup ... --frequency ...``: the layered plate's calculator.

Parses the layup options, calls :func:`dispersion.api.layup` and
:func:`dispersion.api.layered_lamb_modes`, renders the table (with ``--mode-shape``: one mode
through the thickness, :func:`dispersion.answers.mode_shape_table.mode_shapes`).
"""
from __future__ import annotations

import argparse

from dispersion.cli.options import families, real
from dispersion.errors import InputError


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The options of a layered plate."""
    p.add_argument("--layup", metavar="LAYUP",
                   help="a layered or anisotropic plate instead of a material: a TOML file "
                        "(FILE.toml: [[layer]] material, thickness, angle; [[interface]] "
                        "springs), layers material:thickness_mm[:angle],... bottom up (e.g. "
                        "steel:0.71,aluminium:0.29), or a layup such as [0/90]s with --ply "
                        "and --ply-thickness")
    p.add_argument("--ply", metavar="NAME",
                   help="with a layup string such as [0/90]s: the ply (T800/913, or a table "
                        "material)")
    p.add_argument("--ply-thickness", type=real("--ply-thickness", 0, lo_open=True),
                   metavar="MM", help="with --ply: the thickness of one ply in mm")
    p.add_argument("--angle", metavar="DEG",
                   help="with --layup: direction of the waves in degrees from the plate's 0 "
                        "deg axis, in [-360, 360] (default: 0); several (a,b,c or a grid "
                        "START:STOP:COUNT, e.g. 0:90:19) with one frequency: the slowness "
                        "curves, every mode at each direction")
    p.add_argument("--damping", type=real("--damping", 0, 1, hi_open=True), metavar="ETA",
                   help="with --layup: hysteretic loss factor eta of every layer, moduli "
                        "C (1 - i eta), in [0, 1): complex wavenumbers and the attenuation in "
                        "dB/m (default: 0)")
    p.add_argument("--modes", metavar="FAMILIES",
                   help="mode families to solve, comma separated: S, A, SH (symmetric plates; "
                        "with --layup also L for the Lamb modes of an unsymmetric stack, M "
                        "for coupled ones) (default: all)")
    p.add_argument("--zgv", action="store_true",
                   help="with --layup: also the zero-group-velocity points of the plate up to "
                        "5 %% above the highest frequency (an undamped plate; seconds)")


def requested(args) -> bool:
    return getattr(args, "layup", None) is not None


#: Where the layup options apply (read by :data:`dispersion.cli.frequency.RULES`).
RULES = [
    ("--ply", requested, "with --layup"),
    ("--ply-thickness", requested, "with --layup"),
    ("--angle", requested, "with --layup"),
    ("--damping", requested, "with --layup"),
    ("--zgv", requested, "with --layup (the isotropic calculator lists its ZGV points always)"),
]


def run(args) -> int:
    from dispersion.api import layered_lamb_modes, layup
    from dispersion.cli.options import frequencies
    from dispersion.cli.outputs import check_outputs, warn_failures, write_outputs
    from dispersion.plotting.lamb import figure_mode_table

    from dispersion.cli.options import angles

    directions = [0.0] if args.angle is None else angles(args.angle)
    plate = layup(args.layup, ply=args.ply, ply_thickness_mm=args.ply_thickness,
                  direction=directions[0] if len(directions) == 1 else 0.0,
                  damping=0.0 if args.damping is None else args.damping)
    if len(directions) > 1:
        if args.evanescent:
            raise InputError("--evanescent applies to one direction, not with several --angle")
        return _slowness(args, plate, directions)
    if args.evanescent:
        if args.zgv or not plate.lossless:
            raise InputError("--evanescent: the evanescent modes of an undamped plate; drop "
                             f"{'--zgv' if args.zgv else '--damping'}")
        from dispersion.cli import evanescent

        return evanescent.run(args, plate)
    if args.zgv and not plate.lossless:
        raise InputError("--zgv: zero-group-velocity points of a damped plate are not computed "
                         "(its group velocity is not); drop --zgv or --damping")
    check_outputs(args, "branches")
    if args.fd is not None:
        freq = {"fd_mhz_mm": frequencies(args.fd, "--fd", units=None)}
    else:
        freq = {"frequency_khz": frequencies(args.frequency, "--frequency")}
    count = len(next(iter(freq.values())))
    if args.mode_shape is not None and count != 1:
        raise InputError(f"--mode-shape needs exactly one frequency (at most 1), got {count}")
    table = layered_lamb_modes(plate, families=families(args), zgv=args.zgv, **freq)
    warn_failures(table, args)
    if args.mode_shape is not None:
        from dispersion.answers.mode_shape_table import mode_shapes
        from dispersion.plotting.lamb import figure_mode_shapes

        write_outputs(args, mode_shapes(table, args.mode_shape), figure_mode_shapes)
        return 0
    write_outputs(args, table, figure_mode_table)
    return 0


def _slowness(args, plate, directions) -> int:
    """Several directions: the slowness curves at the one frequency."""
    from dispersion.api import slowness_curves
    from dispersion.cli.options import frequencies
    from dispersion.cli.outputs import check_outputs, warn_failures, write_outputs
    from dispersion.plotting.slowness import figure_slowness

    if args.zgv:
        raise InputError("--zgv applies to one direction, not with several --angle")
    if args.mode_shape is not None:
        raise InputError("--mode-shape applies to one direction, not with several --angle")
    if args.fd is not None:
        f = [v * 1e3 / plate.total_thickness_mm for v in frequencies(args.fd, "--fd",
                                                                      units=None)]
    else:
        f = frequencies(args.frequency, "--frequency")
    if len(f) != 1:
        raise InputError(f"several --angle (slowness curves) need exactly one frequency, got "
                         f"{len(f)}")
    check_outputs(args, "branches")
    table = slowness_curves(plate, f[0], directions, families=families(args))
    warn_failures(table, args)
    write_outputs(args, table, figure_slowness)
    return 0
