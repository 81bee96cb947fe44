"""What a command writes, drawn from its result: one ``--format`` vocabulary, files checked
before any work, at most one stream on standard output.

Every command that answers with a table adds the same options (:func:`add_outputs`):
``--format`` (what goes to stdout: :data:`dispersion.rendering.FORMATS`; default: an aligned
table on a terminal, CSV when piped), and named files ``--csv FILE``, ``--json FILE``,
``--figure FILE`` (``-``: stdout, except for a figure). With named files nothing else goes to
stdout unless ``--format`` is given too; two outputs never share stdout. The result renders
itself (:class:`dispersion.rendering.Rendered`); a figure is drawn by the function the command
names. The CSV and the figure are written as one unit (both new, or both old): a stream (a
named pipe or device) cannot be part of one, so among several named outputs each must be a
file, refused up front naming its option. No output may name an input of the command (a
``--mass-rule`` file, a claims file), through any path, link or hard link.

>>> import argparse
>>> stdout_format(argparse.Namespace(format=None), piped="csv")   # stdout is not a terminal
'csv'
"""
from __future__ import annotations

import io
import sys

from dispersion.errors import InputError

__all__ = ["FIGURE_SUFFIXES", "add_outputs", "check_figure", "check_outputs", "emit",
           "progress_bar", "stdout_format", "warn_failures", "write_outputs"]

#: File endings a ``--figure`` may have (matplotlib writes each of them without extras).
FIGURE_SUFFIXES = (".png", ".pdf", ".svg")


def _formats():
    from dispersion.rendering import FORMATS

    return FORMATS


def add_outputs(p, *, csv: bool = True, json: bool = True, figure: str | None = None,
                piped: str = "csv", formats=None) -> None:
    """``--format`` and the named files of a command; ``figure`` says what its figure shows
    (None: the command has none)."""
    from dispersion.cli.options import choice, lazy_help

    names = formats or _formats
    p.add_argument("--format", type=choice("--format", names), default=None, metavar="FORMAT",
                   help=lazy_help("what goes to stdout, one of {names} (default: an aligned "
                                  f"table on a terminal, {piped} when piped; with a named file, "
                                  "nothing unless given)", names))
    if csv:
        p.add_argument("--csv", metavar="FILE",
                       help="write the table as CSV to FILE ('-': stdout), after # lines "
                            "naming the inputs and every failure")
    if json:
        p.add_argument("--json", metavar="FILE",
                       help="write the result as JSON to FILE ('-': stdout)")
    if figure:
        p.add_argument("--figure", metavar="FILE",
                       help=f"write the figure ({figure}) to FILE (.png, .pdf or .svg)")
    p.set_defaults(piped_format=piped)


def stdout_format(args, piped: str = "csv") -> str | None:
    """What goes to stdout: ``--format``, else text on a terminal and ``piped`` otherwise;
    None when named files are written and ``--format`` was not given."""
    if args.format is not None:
        return args.format
    if any(getattr(args, opt, None) for opt in ("csv", "json", "figure")):
        return None
    return "text" if sys.stdout.isatty() else piped


def check_figure(path: str, command: str, option: str = "--figure") -> None:
    """Refuse, before any work, a figure path that cannot receive a figure of ``command``:
    a wrong ending, ``-``, a folder, an unwritable place, or no matplotlib installed.

    >>> check_figure("out.txt", "impact")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: --figure must name a file ending in one of .png, .pdf, .svg, got 'out.txt'
    """
    from dispersion.io import check_output_file
    from dispersion.plotting import require_matplotlib

    if not str(path).lower().endswith(FIGURE_SUFFIXES):
        raise InputError(f"{option} must name a file ending in one of "
                         f"{', '.join(FIGURE_SUFFIXES)}, got {path!r}")
    check_output_file(path, option=option, allow_stdout=False, suffixes=FIGURE_SUFFIXES)
    require_matplotlib(f"{command} {option}")


#: Input files of the commands: the attribute argparse gives them, and their name in messages.
INPUTS = (("mass_rule", "--mass-rule"), ("files", "claims"))


def check_outputs(args, command: str) -> None:
    """Every named output checked before any work: writable, distinct, apart from every
    input file of the command, one stdout stream, no stream among several files."""
    from dispersion.io import check_output_file, unit_target
    from dispersion.ownership import check_apart, same_file

    files = {opt: getattr(args, opt[2:], None) for opt in ("--csv", "--json", "--figure",
                                                            "--junit")}
    files = {opt: path for opt, path in files.items() if path is not None}
    # an output that is an input would replace it: refused before the input is even read
    check_apart(files, {name: getattr(args, attr, None) or () for attr, name in INPUTS})
    streams = [opt for opt, path in files.items() if path == "-"]
    if args.format is not None and files:
        streams.append("--format")
    if len(streams) > 1:
        raise InputError(f"{' and '.join(streams)} would both write to stdout: give one of "
                         "them, and the other a FILE")
    for opt, path in files.items():
        if opt == "--figure":
            check_figure(path, command)
        else:
            check_output_file(path, option=opt)
    named = {opt: path for opt, path in files.items() if path != "-"}
    targets = {}
    for opt, path in named.items():
        target = unit_target(path)
        if target is None:
            if len(named) > 1:  # it would be written after the unit, which may be replaced
                others = " and ".join(o for o in named if o != opt)
                raise InputError(f"{opt} {path} is a stream (a named pipe or device), which "
                                 f"cannot be written as one unit with {others} (all new or all "
                                 "old): write it on its own, or to a file")
            continue
        for other, seen in targets.items():
            if same_file(seen, target):
                raise InputError(f"{other} and {opt} must name two different files, got "
                                 f"{named[other]!r} and {path!r}")
        targets[opt] = target


def emit(path: str, text: str, option: str | None = None) -> None:
    """Write ``text`` to ``path`` atomically, or to standard output for ``-``."""
    if path == "-":
        sys.stdout.write(text)
    else:
        from dispersion.io import write_text

        write_text(path, text, option=option)


def write_outputs(args, result, figure=None, extra=()) -> None:
    """``result`` to stdout in :func:`stdout_format`, and to each named file; ``figure``
    (a function of the result returning a Figure) for ``--figure``; ``extra`` more
    ``(option, path, text)`` of the command (``verify --junit``). The named files are one
    unit; a stream (``-``, or a device or pipe named alone) is written after it."""
    from dispersion.io import unit_target, write_bytes, write_unit
    from dispersion.rendering import render

    fmt = stdout_format(args, getattr(args, "piped_format", "csv"))
    if fmt is not None:
        sys.stdout.write(render(result, fmt))
    outputs = []
    if getattr(args, "figure", None):
        buf = io.BytesIO()
        figure(result).savefig(buf, format=args.figure.rsplit(".", 1)[-1].lower(), dpi=150)
        outputs.append(("--figure", args.figure, buf.getvalue()))
    for opt, fmt in (("csv", "csv"), ("json", "json")):
        if getattr(args, opt, None):
            outputs.append((f"--{opt}", getattr(args, opt), render(result, fmt)))
    outputs += list(extra)
    unit = {unit_target(p): (o, data) for o, p, data in outputs if unit_target(p) is not None}
    if unit:
        write_unit({target: data for target, (_, data) in unit.items()},
                   option="/".join(o for o, _ in unit.values()))
    for opt, path, data in outputs:
        if unit_target(path) is None:
            emit(path, data, opt) if isinstance(data, str) else write_bytes(path, data,
                                                                            option=opt)


def warn_failures(result, args=None) -> None:
    """One line on stderr when values were not certified (every one is in every output), and
    one per input that looks like a unit mix-up (``args.unit_hints``)."""
    from dispersion.rendering import failure_lines

    for hint in getattr(args, "unit_hints", None) or ():
        print(f"warning: {hint}", file=sys.stderr)
    fails = failure_lines(result)
    if len(fails) == 1:
        print(f"warning: {fails[0]}", file=sys.stderr)
    elif fails:
        print(f"warning: {len(fails)} values not certified, each listed in the output "
              f"('# failure:' lines of CSV, 'failures' of JSON); first: {fails[0]}",
              file=sys.stderr)


def progress_bar(flag, desc: str, unit: str, total: int | None = None):
    """A tqdm bar on stderr (``flag`` None: when stderr is a terminal), or None."""
    if not (sys.stderr.isatty() if flag is None else flag):
        return None
    from tqdm import tqdm

    return tqdm(total=total, desc=desc, unit=unit, file=sys.stderr)
