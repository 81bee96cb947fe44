"""`dispersion series`: JSON interface, --paper table, one-line errors with exit status 2."""
import json
import subprocess
import sys

import pytest
import sympy

from dispersion.cli import main


def run(args, capsys):
    try:
        code = main(args)
    except SystemExit as exc:  # argparse refuses a malformed value (exit status 2)
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


def test_json_interface(capsys):
    code, out, _ = run(["series", "--branch", "A0", "--order", "6", "--format", "json"], capsys)
    rec = json.loads(out)
    assert code == 0 and set(rec) >= {"branch", "mass", "model", "coefficients"}
    nu = sympy.Symbol("nu")
    c6 = sympy.sympify(rec["coefficients"]["6"], locals={"nu": nu})
    assert sympy.cancel(c6 - (2 * nu**2 + 8 * nu - 29) / (45 * (1 - nu) ** 2)) == 0  # eq 18


def test_exact_and_latex(capsys):
    code, out, _ = run(["series", "--exact", "--branch", "S0", "--order", "4", "--format", "latex"],
                       capsys)
    assert code == 0 and "\\kappa^{4}" in out


def test_paper_table(capsys):
    code, out, _ = run(["series", "--paper"], capsys)
    # a table row, or (narrower terminal) a block "(17) S0 kappa^6: differs; ..."
    differs = {line.split(" ")[0] for line in out.splitlines()
               if " differs " in line or ": differs" in line}
    # the paper's two misprints (eq 17 kappa^6, eq 19 kappa^4) differ; the exact series
    # (eqs 14, 15) and the CMM A0 series (eq 18) are printed right
    assert code == 0 and {"(17)", "(19)"} <= differs and "(20)" in out
    assert not differs & {"(14)", "(15)", "(18)"}


@pytest.mark.parametrize("args,msg", [
    (["--nu", "0.5"], "nu must lie in (-1, 0.5)"),
    (["--p", "0"], "--p must be an integer in [1, 24]"),
    (["--n", "2"], "n must be >= p + 1"),
    (["--order", "0"], "--order"),
    (["--mass", "singular", "--gamma-s", "1.5"], "--gamma-s must lie in [0, 1]"),
    (["--r", "0"], "--r must lie in [1/1000, 1000]"),
])
def test_bad_input_one_line_exit_2(args, msg, capsys):
    code, out, err = run(["series", *args], capsys)
    assert code == 2 and msg in err and err.count("\n") == 1 and out == ""


def test_console_script_bad_choice_exit_2(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "dispersion", "series", "--contact", "left"],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr


def test_json_file_written_atomically(tmp_path, capsys):
    target = tmp_path / "s.json"
    assert main(["series", "--branch", "S0", "--order", "4", "--json", str(target)]) == 0
    assert json.loads(target.read_text())["branch"] == "S0"
    assert main(["series", "--nu", "2", "--json", str(tmp_path / "bad.json")]) == 2
    assert not (tmp_path / "bad.json").exists()


@pytest.mark.parametrize("args,msg", [
    (["--exact", "--mass", "lumped"], "--mass applies only to a discrete patch (not with --exact"),
    (["--exact", "--n", "4"], "--n applies only to a discrete patch (not with --exact"),
    (["--model", "x-exact", "--r", "3"], "--r applies only to the Bloch model"),
    (["--model", "x-exact", "--r", "-3"], "--r must lie in [1/1000, 1000]"),
    (["--r", "1e-8"], "--r must lie in [1/1000, 1000]"),
    (["--r", "1e-200"], "--r must lie in [1/1000, 1000]"),
    (["--mass", "lumped", "--gamma-s", "1/2"], "--gamma-s applies only to a singular mass rule"),
    (["--order", "400"], "order must be <= 32"),
    (["--exact", "--order", "100000"], "order must be <= 128"),
    (["--p", "20", "--n", "21"], "--n must satisfy (2n)^2 * order <= 12000"),
    (["--p", "40", "--n", "41"], "--p must be an integer in [1, 24]"),
    (["--p", "1.5"], "--p must be an integer in [1, 24], got '1.5'"),
    (["--order", "abc"], "--order must be an integer (an even power of kappa) in [2, 32]"),
    (["--paper", "--order", "12"], "--order applies only to a series (not with --paper"),
    (["--paper", "--exact"], "--exact applies only to a series (not with --paper"),
    (["--mass", "heavy"], "--mass must be one of"),
    (["--mass", "Singlar"], "did you mean 'singular'?"),
])
def test_options_that_do_not_apply_and_bounds_fail_in_one_line(args, msg, capsys):
    code, out, err = run(["series", *args], capsys)
    assert code == 2 and msg in err and err.count("\n") == 1 and out == ""


def test_csv_with_substituted_nu(capsys):
    # eq 14 at nu = 3/10: 2/(1 - nu) = 20/7, -2 nu^2 / (3 (1 - nu)^3) = -60/343
    code, out, _ = run(["series", "--exact", "--branch", "S0", "--order", "4", "--nu", "0.3",
                        "--format", "csv"], capsys)
    lines = [line for line in out.splitlines() if not line.startswith("#")]
    assert code == 0 and lines == ["branch,power,coefficient", "S0,2,20/7", "S0,4,-60/343"]
    assert "# nu: 3/10" in out  # series --format csv states its inputs (issue 28)


def test_lean_entry_prints_the_exact_series_without_importing_sympy():
    from helpers import lean_series

    rc, sympy_loaded, out = lean_series(["--exact", "--order", "6", "--format", "json"])
    assert (rc, sympy_loaded, out.count("coefficients")) == (0, False, 2)
