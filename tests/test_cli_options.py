"""dispersion.cli.options: one grammar for the number options of every command.

Issue 19 item 5 (fractions wherever the API takes rationals, the same forms everywhere) and
issue 17 item 2 (``series --nu 1e-999999999`` refused at once, not hanging).
"""
from __future__ import annotations

import argparse
import json
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.cli import build_parser, main
from dispersion.cli.options import integer, rational, real

QUICK = settings(max_examples=40, deadline=None, derandomize=True)


def _parse(command: str, *argv: str) -> argparse.Namespace:
    scene = ["signorini-1d"] if command == "impact" else []
    return build_parser(command).parse_args([command, *scene, *argv])


@pytest.mark.parametrize("command, option, attr", [
    ("series", "--nu", "nu"), ("series", "--gamma-s", "gamma_s"), ("series", "--r", "r"),
    ("branches", "--nu", "nu"), ("branches", "--gamma-s", "gamma_s"), ("branches", "--r", "r"),
    ("branches", "--kappa-max", "kappa_max"), ("branches", "--omega-max", "omega_max"),
    ("impact", "--dt", "dt"), ("impact", "--t-end", "t_end"),
])
def test_every_number_option_reads_the_same_forms(command, option, attr):
    # 3/10, 0.3, 3e-1 and Rational(3, 10) are one number wherever a number is asked for
    values = {form: getattr(_parse(command, option, form), attr)
              for form in ("3/10", "0.3", "3e-1", "Rational(3, 10)", "(1 + 2)/10")}
    assert len(set(values.values())) == 1, values
    assert Fraction(values["3/10"]) == Fraction(3, 10) or values["3/10"] == 0.3


def test_fractions_give_the_same_series_as_decimals(capsys):
    outs = []
    for nu, r in (("3/10", "1/2"), ("0.3", "0.5")):
        assert main(["series", "--branch", "S0", "--order", "4", "--nu", nu, "--r", r,
                     "--format", "json"]) == 0
        outs.append(json.loads(capsys.readouterr().out))
    assert outs[0] == outs[1] and outs[0]["nu"] == "3/10"


@pytest.mark.parametrize("argv, words", [
    (["series", "--nu", "1e-999999999"], ("nu", "decimal exponent")),
    (["series", "--gamma-s", "9" * 100], ("--gamma-s", "digits")),
    (["series", "--r", "kappa"], ("r", "'r'")),
    (["branches", "--nu", "1e-999999999"], ("nu", "decimal exponent")),
    (["branches", "--omega-max", "nan"], ("omega-max", "nan")),
    (["branches", "--kappa-max", "1e400"], ("kappa-max", "finite")),
    (["branches", "--count", "1e3"], ("count", "[2, 200000]")),
    (["verify", "--jobs", "0"], ("--jobs", "[1, 64]")),
    (["impact", "signorini-1d", "--dt", "__import__('os')"], ("dt", "number")),
])
def test_malformed_numbers_are_refused_in_one_line_before_work(argv, words, capsys, monkeypatch):
    import dispersion.cli as cli

    monkeypatch.setattr(cli, "run_parsed", lambda args: pytest.fail("the command ran"))
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "error:" in err
    for word in words:
        assert word in err, err


def test_messages_name_the_option_and_its_range():
    with pytest.raises(argparse.ArgumentTypeError, match=r"^count must be an integer in "
                                                          r"\[2, 10\], got 'x'$"):
        integer("count", 2, 10)("x")
    with pytest.raises(argparse.ArgumentTypeError, match=r"omega-max must lie in \(0, 200\], "
                                                          r"got 0$"):
        real("omega-max", 0, 200, lo_open=True)("0")
    with pytest.raises(argparse.ArgumentTypeError, match=r"nu must lie in \(-1, 1/2\)"):
        rational("nu", -1, "1/2", lo_open=True, hi_open=True)("1/2")


PARSERS = [rational("x"), rational("x", -1, "1/2", lo_open=True, hi_open=True),
           rational("r", symbol="r"), real("x"), real("x", 0, 200, lo_open=True),
           integer("n"), integer("n", 2, 10)]
TEXTS = st.one_of(st.text(max_size=30), st.lists(st.sampled_from(
    ["1", "0", "9", ".", "e", "E", "-", "+", "/", "*", "^", "(", ")", "1e999999999", "nan",
     "inf", "r", "nu", "_", "'", "\\", " ", "\uff11", "Rational(", ","]), max_size=12).map("".join))


@QUICK
@given(TEXTS)
def test_random_option_text_is_a_value_in_range_or_one_argparse_error(text):
    for parse in PARSERS:
        try:
            value = parse(text)
        except argparse.ArgumentTypeError as exc:
            assert "\n" not in str(exc)
            continue
        assert value == "r" or isinstance(value, (Fraction, float, int))


def test_reading_a_fraction_loads_no_sympy():
    # the options read rationals with the claims reader, which must stay light: the exact
    # series with --nu 3/10 prints from the flint kernel alone (cli/series.py's promise)
    from helpers import lean_series

    rc, sympy_loaded, out = lean_series(["--exact", "--order", "4", "--nu", "3/10",
                                         "--format", "json"])
    assert (rc, sympy_loaded) == (0, False) and "3/10" in out


# ------------------------------------------------------------------ one material parser
_BRANCHES_FREQUENCY = ["branches", "--exact", "--frequency", "100", "--thickness", "1"]


@pytest.mark.parametrize("material", [
    ["--cl", "6000"], ["--ct", "3000"], ["--material", "steel", "--cl", "6000"],
    ["--cl", "100", "--ct", "5000"], ["--cl", "6000", "--ct", "-3000"],
])
def test_timestep_and_branches_refuse_a_material_with_the_same_line(material, capsys):
    # both commands read --material/--cl/--ct/--rho with options.material_from_args, so the
    # same bad material is refused with the same words (before, timestep had its own parser)
    lines = []
    for argv in (["timestep", *material], [*_BRANCHES_FREQUENCY, *material]):
        assert main(argv) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1
        lines.append(err[0].split(": error: ", 1)[1])
    assert lines[0] == lines[1] and "--" in lines[0]


def test_timestep_and_branches_read_the_same_material():
    from dispersion.cli.options import material_from_args
    from dispersion.materials.materials import user_material

    speeds = ["--cl", "6000", "--ct", "3000"]
    a = material_from_args(_parse("timestep", *speeds), default="steel")
    b = material_from_args(_parse("branches", *speeds))
    assert a == b == user_material(c_L=6000.0, c_T=3000.0)
    assert material_from_args(_parse("timestep"), default="steel").name == "steel"
    assert material_from_args(_parse("branches")) is None
