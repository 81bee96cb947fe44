"""Command line: ``dispersion series | branches | ring | impact | verify | reproduce | bench | timestep | simulate``.

A thin layer over the API. Each subcommand lives in its own module exposing
``register(subparsers)``, which adds the parser and sets ``func(args) -> int``.
Errors print one line to stderr, never a traceback: exit status 2 for bad input
(:class:`~dispersion.errors.InputError`, and argparse's own errors), 1 for other toolkit
errors and for failures of the file system (a full disk, a vanished folder). SIGTERM is
handled like Ctrl-C: the command unwinds (removing its temporaries) and exits 143.

>>> main(["--version"])  # doctest: +ELLIPSIS
dispersion ...
0
"""
from __future__ import annotations

import argparse
import contextlib
import importlib
import re
import signal
import sys
import threading

from dispersion.errors import DispersionError, InputError

_SUBCOMMANDS = ("series", "branches", "ring", "impact", "verify", "reproduce", "bench",
               "timestep", "simulate")


class Terminated(KeyboardInterrupt):
    """SIGTERM arrived: unwound like Ctrl-C, so every writer removes its temporaries."""


def _on_sigterm(signum, frame):
    raise Terminated()


@contextlib.contextmanager
def _sigterm_unwinds():
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, _on_sigterm)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit 2, like InputError
        # "argument --mass: --mass must be ..." says the option once
        message = re.sub(r"^argument (\S+?)(?:/\S+)?: (?=\1 )", "", message)
        self.exit(2, f"{self.prog}: error: {message}\n")


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The ``dispersion`` parser; with ``only``, just that subcommand's module is imported.

    The others get an empty placeholder, so ``dispersion series ...`` pays neither the import
    of sympy nor numpy unless the series command itself needs them.
    """
    parser = _Parser(prog="dispersion",
                     description=f"Command line: dispersion {' | '.join(_SUBCOMMANDS)}.")
    parser.add_argument("--version", action="store_true",
                        help="print the version of the toolkit and exit")
    sub = parser.add_subparsers(dest="command", parser_class=_Parser)
    for name in _SUBCOMMANDS:
        if only is not None and name != only:
            sub.add_parser(name)
            continue
        try:
            module = importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
            continue
        module.register(sub)
    return parser


def version() -> str:
    """Version of the installed distribution (``dispersion-iga``)."""
    from importlib import metadata

    try:
        return metadata.version("dispersion-iga")
    except metadata.PackageNotFoundError:  # pragma: no cover - running from a bare checkout
        from dispersion import __version__

        return __version__


def main(argv: list[str] | None = None) -> int:
    """Parse ``argv`` (default: the process's arguments) and run the command; its exit status.

    Ctrl-C anywhere from here on (while a command's modules load, while it parses, while it
    runs) is one line and status 130, never a traceback.
    """
    try:
        return _main(argv)
    except Terminated:
        print("dispersion: terminated", file=sys.stderr)
        return 143
    except KeyboardInterrupt:
        print("dispersion: interrupted", file=sys.stderr)
        return 130


def _main(argv: list[str] | None) -> int:
    words = sys.argv[1:] if argv is None else list(argv)
    chosen = next((w for w in words if not w.startswith("-")), None)
    parser = build_parser(chosen if chosen in _SUBCOMMANDS else None)
    try:
        args = parser.parse_args(words)
    except SystemExit as exc:  # argparse's one-line error: a status, like InputError's
        if exc.code in (0, None):  # --help: argparse's own exit
            raise
        return exc.code if isinstance(exc.code, int) else 2
    if args.version:
        print(f"dispersion {version()}")
        return 0
    if args.command is None:
        parser.error(f"a command is required: {', '.join(_SUBCOMMANDS)}")
    with _sigterm_unwinds():
        return run_parsed(args)


def _one_line_warning(message, category, filename, lineno, file=None, line=None):
    """A warning as the command line shows it: one line, no source location."""
    print(f"warning: {message}", file=sys.stderr if file is None else file)


def _cli_ways(command: str, ways) -> str:
    """``: use --model x-exact`` for the ways (parameter, value) that ``command`` accepts as
    an option and a value; nothing if it accepts none (no advice it could not follow)."""
    from dispersion.cli.options import PARAMETER_OPTIONS

    sub = build_parser(command)._subparsers._group_actions[0].choices[command]
    actions = {opt: a for a in sub._actions for opt in a.option_strings}
    shown = []
    for name, value in ways:
        action = actions.get(PARAMETER_OPTIONS.get(name, f"--{name.replace('_', '-')}"))
        if action is None:
            continue
        try:
            if action.type is not None:
                action.type(str(value))
        except (argparse.ArgumentTypeError, ValueError, TypeError):
            continue
        shown.append(f"{action.option_strings[0]} {value}")
    return f": use {' or '.join(shown)}" if shown else ""


def run_parsed(args: argparse.Namespace) -> int:
    """Run a parsed subcommand: its exit status, or one line on stderr for every failure."""
    import warnings

    try:
        with warnings.catch_warnings():
            warnings.showwarning = _one_line_warning
            return int(args.func(args) or 0)
    except InputError as exc:  # in the command's words: its options, not Python parameters
        from dispersion.cli.options import cli_words

        if getattr(args, "file_words", False):
            text = str(exc)
        elif getattr(exc, "ways", ()):  # the ways out, as options this command has
            text = cli_words(exc.reason) + _cli_ways(args.command, exc.ways)
        else:
            text = cli_words(str(exc))
        print(f"dispersion {args.command}: error: {text}", file=sys.stderr)
        return 2
    except DispersionError as exc:
        print(f"dispersion {args.command}: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 1
    except BrokenPipeError:  # the reader of stdout went away (e.g. `| head`)
        sys.stderr.close()
        return 1
    except OSError as exc:
        print(f"dispersion {args.command}: error: {exc.strerror or exc}"
              + (f": {exc.filename}" if exc.filename else ""), file=sys.stderr)
        return 1
    except Terminated:
        print("dispersion: terminated", file=sys.stderr)
        return 143
    except KeyboardInterrupt:
        print("dispersion: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
