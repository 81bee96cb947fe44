"""``dispersion branches --frequency/--fd``: the Lamb-wave calculator on the command line.

Parses the frequencies and the material, calls :func:`dispersion.api.lamb_modes` (or
:func:`dispersion.waves.mode_shape_table.mode_shapes` with ``--mode-shape``) and renders the
result. Frequencies: ``200`` (kHz), ``200kHz``, ``0.2MHz``, ``2e5Hz``; lists ``100,200,300``;
grids ``START:STOP:COUNT`` (COUNT points, both ends included), e.g. ``10kHz:1MHz:500``.
"""
from __future__ import annotations

import argparse

from dispersion.cli.options import material_from_args, real
from dispersion.errors import InputError


def _materials():
    from dispersion.waves.materials import MATERIALS

    return sorted(MATERIALS)


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The frequency-axis and material options of ``dispersion branches``."""
    from dispersion.cli.options import choice, lazy_help

    p.add_argument("--material", type=choice("--material", _materials), metavar="NAME",
                   help=lazy_help("material of the plate (CRC handbook rows): {names}; or give "
                                  "--cl/--ct[/--rho], or --youngs-modulus/--nu/--rho",
                                  _materials))
    p.add_argument("--cl", type=real("--cl", 0, lo_open=True),
                   help="longitudinal (bulk) wave speed c_L in m/s")
    p.add_argument("--ct", type=real("--ct", 0, lo_open=True),
                   help="shear wave speed c_T in m/s")
    p.add_argument("--rho", type=real("--rho", 0, lo_open=True),
                   help="density in kg/m^3 (with --cl/--ct, or with --youngs-modulus and --nu)")
    p.add_argument("--youngs-modulus", type=real("--youngs-modulus", 0, lo_open=True),
                   metavar="E", help="Young's modulus E in GPa (with --nu and --rho)")
    p.add_argument("--thickness", type=real("--thickness", 0, lo_open=True),
                   help="plate thickness d = 2h in mm (with a material)")
    p.add_argument("--frequency", metavar="F",
                   help="frequencies f in kHz (or with a unit: 200kHz, 0.2MHz, 2e5Hz); lists "
                        "a,b,c and grids START:STOP:COUNT (both ends included); with --exact, "
                        "a material and --thickness: every propagating mode at each")
    p.add_argument("--fd", metavar="FD",
                   help="frequency-thickness products f d in MHz mm (lists and grids as for "
                        "--frequency)")
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
    p.add_argument("--angle", type=real("--angle", -360, 360),
                   help="with --layup: direction of the waves in degrees from the plate's 0 "
                        "deg axis, in [-360, 360] (default: 0)")
    p.add_argument("--modes", metavar="FAMILIES",
                   help="mode families to solve, comma separated: S, A, SH (symmetric plates; "
                        "with --layup also L for the Lamb modes of an unsymmetric stack, M "
                        "for coupled ones) (default: all)")
    p.add_argument("--mode-shape", metavar="MODE",
                   help="with one frequency: displacements and stresses through the thickness "
                        "of MODE (S0, a1, SH0, ...) instead of the mode table")


def requested(args) -> bool:
    return args.frequency is not None or args.fd is not None


def _layup(a) -> bool:
    return getattr(a, "layup", None) is not None


def _material_given(a) -> bool:
    return any(getattr(a, k, None) is not None for k in ("material", "cl", "ct",
                                                           "youngs_modulus"))


#: Where the calculator's options apply (read by :data:`dispersion.cli.branches.RULES`).
RULES = [
    ("--frequency", lambda a: a.exact, "with --exact (the exact Rayleigh-Lamb and SH modes)"),
    ("--fd", lambda a: a.exact and a.frequency is None,
     "with --exact, instead of --frequency (one input axis)"),
    ("--mode-shape", lambda a: requested(a) and not _layup(a),
     "with --frequency or --fd (an isotropic plate)"),
    ("--thickness", lambda a: _material_given(a) and not _layup(a),
     "with a material (--material, --cl/--ct or --youngs-modulus/--nu/--rho)"),
    ("--layup", lambda a: requested(a) and not _material_given(a),
     "with --frequency or --fd, instead of a material"),
    ("--ply", _layup, "with --layup"),
    ("--ply-thickness", _layup, "with --layup"),
    ("--angle", _layup, "with --layup"),
    ("--modes", requested, "with --frequency or --fd"),
    ("--rho", lambda a: a.cl is not None or a.ct is not None or a.youngs_modulus is not None,
     "to a user material (--cl/--ct, or --youngs-modulus/--nu)"),
    ("--nu", lambda a: a.youngs_modulus is not None or not _material_given(a),
     "without a material (a material fixes nu from c_L and c_T), or with --youngs-modulus"),
]


def _families(args):
    if args.modes is None:
        return None
    names = [w.strip().upper() for w in args.modes.split(",") if w.strip()]
    allowed = ("S", "A", "SH", "L", "M")
    bad = [w for w in names if w not in allowed]
    if bad or not names:
        raise InputError(f"--modes must be a comma-separated list of {', '.join(allowed)}, got "
                         f"{args.modes[:40]!r}")
    return tuple(dict.fromkeys(names))


def _run_layup(args) -> int:
    from dispersion.answers.layered_mode_table import layered_lamb_modes
    from dispersion.cli.options import frequencies
    from dispersion.cli.outputs import check_outputs, warn_failures, write_outputs
    from dispersion.continuum.layup_file import plate_from_string, read_layup
    from dispersion.plotting.lamb import figure_mode_table

    direction = 0.0 if args.angle is None else args.angle
    if args.layup.strip().lower().endswith(".toml"):
        if args.ply is not None or args.ply_thickness is not None:
            raise InputError("--ply and --ply-thickness go with a layup string, not a file")
        plate = read_layup(args.layup)
        if args.angle is not None:
            plate = plate.turned(direction)
    else:
        plate = plate_from_string(args.layup, ply=args.ply, ply_thickness_mm=args.ply_thickness,
                                  direction=direction)
    check_outputs(args, "branches")
    families = _families(args)
    if args.fd is not None:
        table = layered_lamb_modes(plate, fd_mhz_mm=frequencies(args.fd, "--fd", units=None),
                                   families=families)
    else:
        table = layered_lamb_modes(plate, frequency_khz=frequencies(args.frequency,
                                                                    "--frequency"),
                                   families=families)
    warn_failures(table, args)
    write_outputs(args, table, figure_mode_table)
    return 0


def run(args) -> int:
    from dispersion.api import lamb_modes
    from dispersion.cli.options import frequencies
    from dispersion.cli.outputs import check_outputs, write_outputs

    if _layup(args):
        return _run_layup(args)
    material = material_from_args(args)
    if material is None or args.thickness is None:
        raise InputError("--frequency/--fd need a material (--material, --cl/--ct or "
                         "--youngs-modulus/--nu/--rho) and --thickness (d in mm)")
    check_outputs(args, "branches")
    kinds = {} if args.modes is None else {"kinds": _families(args)}
    if args.fd is not None:
        table = lamb_modes(material, args.thickness, fd_mhz_mm=frequencies(args.fd, "--fd",
                                                                            units=None), **kinds)
    else:
        table = lamb_modes(material, args.thickness,
                           frequency_khz=frequencies(args.frequency, "--frequency"), **kinds)
    if args.mode_shape is not None:
        from dispersion.plotting.lamb import figure_mode_shapes
        from dispersion.waves.mode_shape_table import mode_shapes

        if table.frequency_khz.size != 1:
            raise InputError(f"--mode-shape needs exactly one frequency (at most 1), got "
                             f"{table.frequency_khz.size}")
        write_outputs(args, mode_shapes(table, args.mode_shape), figure_mode_shapes)
        return 0
    from dispersion.cli.outputs import warn_failures
    from dispersion.plotting.lamb import figure_mode_table

    warn_failures(table, args)
    write_outputs(args, table, figure_mode_table)
    return 0
