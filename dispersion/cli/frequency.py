"""``dispersion branches --frequency/--fd``: the Lamb-wave calculator on the command line.

Parses the frequencies and the material, calls :func:`dispersion.api.lamb_modes` (or
:func:`dispersion.answers.mode_shape_table.mode_shapes` with ``--mode-shape``) and renders the
result. Frequencies: ``200`` (kHz), ``200kHz``, ``0.2MHz``, ``2e5Hz``; lists ``100,200,300``;
grids ``START:STOP:COUNT`` (COUNT points, both ends included), e.g. ``10kHz:1MHz:500``.
"""
from __future__ import annotations

import argparse

from dispersion.cli import layup
from dispersion.cli.options import length, material_from_args, real
from dispersion.errors import InputError


def _materials():
    from dispersion.materials.materials import MATERIALS

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
    p.add_argument("--thickness", type=length("--thickness", "mm", 0, lo_open=True),
                   help="plate thickness d = 2h in mm, or with a unit (3mm, 0.3cm, 0.003m), "
                        "with a material")
    p.add_argument("--frequency", metavar="F",
                   help="frequencies f in kHz (or with a unit: 200kHz, 0.2MHz, 2e5Hz); lists "
                        "a,b,c and grids START:STOP:COUNT (both ends included); with --exact, "
                        "a material and --thickness: every propagating mode at each")
    p.add_argument("--fd", metavar="FD",
                   help="frequency-thickness products f d in MHz mm (lists and grids as for "
                        "--frequency)")
    layup.add_arguments(p)
    p.add_argument("--evanescent", action="store_true",
                   help="with --exact: the evanescent modes instead of the propagating ones "
                        "(imaginary and complex k, Im k > 0, decaying towards +x; Re k >= 0): "
                        "Re k, Im k and the decay in dB/m and dB per thickness, each root "
                        "certified and their number counted (seconds per frequency; at most "
                        "20 frequencies)")
    p.add_argument("--decay-max", type=real("--decay-max", 0, 200, lo_open=True),
                   metavar="DB", help="with --evanescent: the largest decay searched, in dB "
                                      "per plate thickness, in (0, 200] (default: 60)")
    p.add_argument("--mode-shape", metavar="MODE",
                   help="with one frequency: displacements and stresses through the thickness "
                        "of MODE (S0, a1, SH0, ...) instead of the mode table; with --layup "
                        "also the energy densities and power flow, in physical units, with the "
                        "interfaces")


def requested(args) -> bool:
    return args.frequency is not None or args.fd is not None


def _layup(a) -> bool:
    return layup.requested(a)


def _material_given(a) -> bool:
    return any(getattr(a, k, None) is not None for k in ("material", "cl", "ct",
                                                           "youngs_modulus"))


#: Where the calculator's options apply (read by :data:`dispersion.cli.branches.RULES`).
RULES = [
    ("--frequency", lambda a: a.exact, "with --exact (the exact Rayleigh-Lamb and SH modes)"),
    ("--fd", lambda a: a.exact and a.frequency is None,
     "with --exact, instead of --frequency (one input axis)"),
    ("--evanescent", requested, "with --frequency or --fd"),
    ("--decay-max", lambda a: a.evanescent, "with --evanescent"),
    ("--mode-shape", lambda a: requested(a) and not a.evanescent,
     "with --frequency or --fd (a propagating mode, not with --evanescent)"),
    ("--thickness", lambda a: _material_given(a) and not _layup(a),
     "with a material (--material, --cl/--ct or --youngs-modulus/--nu/--rho)"),
    ("--layup", lambda a: requested(a) and not _material_given(a),
     "with --frequency or --fd, instead of a material"),
    ("--modes", requested, "with --frequency or --fd"),
    *layup.RULES,
    ("--rho", lambda a: a.cl is not None or a.ct is not None or a.youngs_modulus is not None,
     "to a user material (--cl/--ct, or --youngs-modulus/--nu)"),
    ("--nu", lambda a: not _layup(a) and (a.youngs_modulus is not None
                                          or not _material_given(a)),
     "without a material or a layup (a material fixes nu from c_L and c_T, a layup's layers "
     "their own), or with --youngs-modulus"),
]


def run(args) -> int:
    from dispersion.api import lamb_modes
    from dispersion.cli.options import frequencies
    from dispersion.cli.outputs import check_outputs, write_outputs

    if _layup(args):
        return layup.run(args)
    material = material_from_args(args)
    if material is None or args.thickness is None:
        raise InputError("--frequency/--fd need a material (--material, --cl/--ct or "
                         "--youngs-modulus/--nu/--rho) and --thickness (d in mm)")
    check_outputs(args, "branches")
    if args.evanescent:
        from dispersion.cli import evanescent

        return evanescent.run(args, material, args.thickness)
    kinds = {} if args.modes is None else {"kinds": layup.families(args)}
    if args.fd is not None:
        table = lamb_modes(material, args.thickness, fd_mhz_mm=frequencies(args.fd, "--fd",
                                                                            units=None), **kinds)
    else:
        table = lamb_modes(material, args.thickness,
                           frequency_khz=frequencies(args.frequency, "--frequency"), **kinds)
    if args.mode_shape is not None:
        from dispersion.plotting.lamb import figure_mode_shapes
        from dispersion.answers.mode_shape_table import mode_shapes

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

