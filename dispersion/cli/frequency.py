"""``dispersion branches --frequency/--fd``: every propagating mode at given frequencies.

Options added to ``dispersion branches`` by :func:`add_arguments`; :func:`run` is used when
``--frequency`` or ``--fd`` is given (with ``--exact``, a material and ``--thickness``). It
prints (or writes with ``--csv``/``--json``) one row per mode and frequency, with ``#`` lines
for the inputs, the units, the cut-offs and the zero-group-velocity points; ``--figure`` draws
the curves in physical units; ``--mode-shape LABEL`` gives the displacements and stresses
through the thickness of that mode at one frequency.

Frequencies: ``200`` (kHz), ``200kHz``, ``0.2MHz``, ``2e5Hz``; lists ``100,200,300``; grids
``START:STOP:COUNT`` (COUNT points, both ends included), e.g. ``10kHz:1MHz:500``.
"""
from __future__ import annotations

import argparse
import math
import re
import sys
from typing import TYPE_CHECKING

from dispersion.cli.options import material_from_args, real
from dispersion.cli.outputs import EMPTY_NOTE, cell, check_figure, csv_text, emit
from dispersion.errors import InputError

if TYPE_CHECKING:  # numpy is imported where used: the parser (and --help) stays light
    import numpy as np

#: Most frequencies of one request (a grid's COUNT included); the scan bound of
#: :data:`dispersion.waves.frequency.MAX_SCAN_SAMPLES` applies as well.
MAX_FREQUENCIES = 100_000
_UNITS = {"hz": 1e-3, "khz": 1.0, "mhz": 1e3}
_NUMBER = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([a-zA-Z]*)\s*$")


def _value(text: str, option: str, units: dict | None) -> float:
    m = _NUMBER.match(text)
    unit = m.group(2).lower() if m else ""
    if not m or (unit and (units is None or unit not in units)):
        allowed = f" with an optional unit ({', '.join(('Hz', 'kHz', 'MHz'))})" if units else ""
        raise InputError(f"{option} must be numbers{allowed}, lists a,b,c or grids "
                         f"START:STOP:COUNT; got {text!r}")
    return float(m.group(1)) * (units[unit] if unit else 1.0)


def parse_values(text: str, option: str, units: dict | None = _UNITS) -> np.ndarray:
    """Numbers, lists and ``START:STOP:COUNT`` grids of ``text`` (kHz unless a unit is given).

    >>> parse_values("200", "--frequency").tolist(), parse_values("0.1MHz,150", "--frequency").tolist()
    ([200.0], [100.0, 150.0])
    >>> parse_values("10kHz:1MHz:3", "--frequency").tolist()
    [10.0, 505.0, 1000.0]
    """
    import numpy as np

    out = []
    for token in str(text).split(","):
        parts = token.split(":")
        if len(parts) == 1:
            out.append(np.array([_value(parts[0], option, units)]))
        elif len(parts) == 3:
            lo, hi = _value(parts[0], option, units), _value(parts[1], option, units)
            try:
                count = int(parts[2])
            except ValueError:
                raise InputError(f"{option}: COUNT of START:STOP:COUNT must be an integer, "
                                 f"got {parts[2]!r}") from None
            if not 1 <= count <= MAX_FREQUENCIES:
                raise InputError(f"{option}: COUNT must be an integer in [1, "
                                 f"{MAX_FREQUENCIES}], got {count}")
            if not hi > lo:
                raise InputError(f"{option}: a grid START:STOP:COUNT needs STOP > START, got "
                                 f"{token!r}")
            out.append(np.linspace(lo, hi, count))
        else:
            raise InputError(f"{option} must be numbers, lists a,b,c or grids START:STOP:COUNT;"
                             f" got {token!r}")
    values = np.concatenate(out)
    if values.size > MAX_FREQUENCIES:
        raise InputError(f"{option} must give at most {MAX_FREQUENCIES} values, got "
                         f"{values.size}")
    if not np.all(np.isfinite(values)) or np.any(values <= 0):
        raise InputError(f"{option} values must be finite and > 0, got {text!r}")
    return values


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The frequency-axis and material options of ``dispersion branches``."""
    p.add_argument("--frequency", metavar="F",
                   help="frequencies f in kHz (or with a unit: 200kHz, 0.2MHz, 2e5Hz); lists "
                        "a,b,c and grids START:STOP:COUNT; needs --exact, a material and "
                        "--thickness; replaces the kappa grid")
    p.add_argument("--fd", metavar="FD",
                   help="frequency-thickness products f d in MHz mm (lists and grids as for "
                        "--frequency)")
    p.add_argument("--mode-shape", metavar="MODE",
                   help="with one --frequency/--fd: displacements and stresses through the "
                        "thickness of MODE (e.g. S0, A1, SH0) instead of the mode table")
    p.add_argument("--rho", type=real("rho", 0, lo_open=True), default=None,
                   help="density in kg/m^3 (with --cl/--ct, or with --youngs-modulus and --nu)")
    p.add_argument("--youngs-modulus", type=real("youngs-modulus", 0, lo_open=True),
                   default=None, metavar="E",
                   help="Young's modulus E in GPa (with --nu and --rho: a user material)")
    p.add_argument("--json", help="with --frequency/--fd: write the table as JSON to FILE "
                                  "('-': stdout)")


def requested(args) -> bool:
    return args.frequency is not None or args.fd is not None


def _check(args):
    if args.frequency is not None and args.fd is not None:
        raise InputError("--frequency and --fd must not be given together (one input axis)")
    if not args.exact:
        raise InputError("--frequency/--fd need --exact (the exact Rayleigh-Lamb and SH modes; "
                         "discrete branches are on the kappa grid only)")
    for opt, val in (("--kappa-min", args.kappa_min), ("--kappa-max", args.kappa_max),
                     ("--count", args.count), ("--omega-max", args.omega_max)):
        if val is not None:
            raise InputError(f"{opt} does not apply with --frequency/--fd (the frequency is "
                             "the input axis)")
    mat = material_from_args(args)
    if mat is None or args.thickness is None:
        raise InputError("--frequency/--fd need a material (--material, --cl/--ct or "
                         "--youngs-modulus/--nu/--rho) and --thickness (d in mm)")
    if args.nu is not None and args.youngs_modulus is None:
        raise InputError("--nu does not apply with a material (nu follows from c_L and c_T)")
    from dispersion.io import check_output_file

    for opt, path in (("--csv", args.csv), ("--json", args.json)):
        if path is not None:
            check_output_file(path, option=opt)
    if args.figure is not None:
        check_figure(args.figure, "branches")
    if args.fd is not None:
        values = parse_values(args.fd, "--fd", units=None)
        return mat, None, values
    return mat, parse_values(args.frequency, "--frequency"), None


def _header(table, extra: dict) -> list[str]:
    from dispersion.results import package_versions

    lines = [f"# {k}: {v}" for k, v in table.inputs().items()]
    lines += [f"# {k}: {v}" for k, v in extra.items()]
    from dispersion.waves.mode_table import COLUMNS

    lines.append("# units: " + ", ".join(COLUMNS))
    lines.append(f"# {EMPTY_NOTE}")
    lines += [f"# cut-off {lab}: {f:.10g} kHz" for lab, f in table.cutoffs_khz().items()]
    lines += [f"# ZGV {p['mode']}: f = {p['f [kHz]']:.10g} kHz, fd = {p['fd [MHz mm]']:.10g} "
              f"MHz mm, c_p = {p['c_p [m/s]']:.10g} m/s" for p in table.zgv()]
    lines += [f"# failure at f = {x['f [kHz]']:.10g} kHz ({x['family']}): {x['reason']}"
              for x in table.failures()]
    lines.append(f"# dispersion-iga: {package_versions(('dispersion-iga',))['dispersion-iga']}")
    return lines


def render_text(rows: list[dict], header: list[str]) -> str:
    lines = list(header)
    if rows:
        cols = list(rows[0])
        width = [max(len(c), 12) for c in cols]
        lines.append("  ".join(f"{c:>{w}}" for c, w in zip(cols, width)))
        for row in rows:
            lines.append("  ".join(
                f"{v:>{w}.7g}" if isinstance(v, float) and math.isfinite(v)
                else f"{cell(v):>{w}}" for v, w in zip(row.values(), width)))
    return "\n".join(lines) + "\n"


def _fields(table, label: str):
    """Through-thickness fields of every root labelled ``label`` (one frequency)."""
    import numpy as np

    from dispersion.waves.mode_shapes import exact_mode_fields
    from dispersion.waves.sh import sh_mode_shape

    r = table.roots
    picks = [i for i, lab in enumerate(r.label) if lab == label]
    if not picks:
        raise InputError(f"--mode-shape must be one of the modes propagating at this "
                         f"frequency ({', '.join(dict.fromkeys(r.label))}), got {label!r}")
    y = np.linspace(-1.0, 1.0, 41)
    out = []
    for i in picks:
        kappa, W = float(r.kappa[i]), float(r.omega[r.index[i]])
        k = kappa / table.h_mm
        name = f"{label}, f = {table.frequency_khz[r.index[i]]:.6g} kHz, k = {k:.6g} rad/mm"
        if label.startswith("SH"):
            u, du = sh_mode_shape(label, y)
            fl = {"u_z": u, "sigma_yz": du, "sigma_xz": kappa * u}
        else:
            f = exact_mode_fields(label[0], kappa, W, table.nu, y)
            fl = {key: f[key] for key in ("u_x", "u_y", "sigma_xx", "sigma_yy", "sigma_xy")}
        out.append({"name": name, "y [mm]": y * table.h_mm, **fl, "k [rad/mm]": k})
    return out


def _field_rows(fields) -> list[dict]:
    rows = []
    for fl in fields:
        keys = [k for k in fl if k not in ("name", "y [mm]", "k [rad/mm]")]
        for j, y in enumerate(fl["y [mm]"]):
            row = {"k [rad/mm]": fl["k [rad/mm]"], "y [mm]": float(y)}
            row.update({k: float(fl[k][j]) for k in keys})
            rows.append(row)
    return rows


def run(args) -> int:
    from dispersion.waves.mode_table import lamb_modes

    mat, f_khz, fd = _check(args)
    if args.mode_shape is not None:
        count = (f_khz if fd is None else fd).size
        if count != 1:
            raise InputError(f"--mode-shape needs exactly one frequency (at most 1), got {count}")
    table = lamb_modes(mat, args.thickness, frequency_khz=f_khz, fd_mhz_mm=fd)
    for x in table.failures():
        print(f"warning: f = {x['f [kHz]']:.6g} kHz ({x['family']}): {x['reason']}",
              file=sys.stderr)
    if args.mode_shape is not None:
        fields = _fields(table, args.mode_shape)
        rows = _field_rows(fields)
        from dispersion.waves.mode_shapes import FIELD_NORMALISATION

        header = _header(table, {"mode shape": args.mode_shape,
                                 "normalisation": FIELD_NORMALISATION})
    else:
        fields = None
        rows = table.rows()
        header = _header(table, {})
    if args.figure:
        from dispersion.io import save_figure

        if fields is not None:
            from dispersion.plotting.lamb import figure_mode_fields

            fig = figure_mode_fields(fields, f"{args.mode_shape}: {table.title()}")
        else:
            from dispersion.plotting.lamb import figure_dispersion

            fig = figure_dispersion(table.curves(), table.title(), table.zgv(),
                                    table.cutoffs_khz())
        save_figure(fig, args.figure, dpi=150)
    if args.json:
        from dispersion.results import dumps, envelope

        env = envelope("branches", {"rows": rows, "cutoffs [kHz]": table.cutoffs_khz(),
                                    "zgv": table.zgv(), "failures": table.failures()},
                       inputs=table.inputs())
        emit(args.json, dumps(env))
    if args.csv:
        emit(args.csv, csv_text(rows, header))
    if not (args.csv or args.json or args.figure):
        if args.format == "json":
            from dispersion.results import dumps, envelope

            emit("-", dumps(envelope("branches", {
                "rows": rows, "cutoffs [kHz]": table.cutoffs_khz(), "zgv": table.zgv(),
                "failures": table.failures()}, inputs=table.inputs())))
        elif args.format == "text":
            emit("-", render_text(rows, header))
        else:
            emit("-", csv_text(rows, header))
    return 0
