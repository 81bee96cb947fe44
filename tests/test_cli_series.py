"""`dispersion series`: JSON interface, --paper table, one-line errors with exit status 2."""
import json
import subprocess
import sys

import pytest
import sympy

from dispersion.cli import main


def run(args, capsys):
    code = main(args)
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
    assert code == 0 and out.count("differs") == 2 and "(20)" in out


@pytest.mark.parametrize("args,msg", [
    (["--nu", "0.5"], "nu must lie in (-1, 0.5)"),
    (["--p", "0"], "degree p"),
    (["--n", "2"], "n must be >= p + 1"),
    (["--order", "0"], "order"),
    (["--mass", "singular", "--gamma-s", "1.5"], "gamma_s must lie in [0, 1]"),
    (["--r", "0"], "aspect ratio r"),
])
def test_bad_input_one_line_exit_2(args, msg, capsys):
    code, out, err = run(["series", *args], capsys)
    assert code == 2 and msg in err and err.count("\n") == 1 and out == ""


def test_console_script_bad_choice_exit_2(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "dispersion", "series", "--contact", "left"],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr


def test_out_file_written_atomically(tmp_path, capsys):
    target = tmp_path / "s.json"
    assert main(["series", "--branch", "S0", "--order", "4", "--format", "json",
                 "--out", str(target)]) == 0
    assert json.loads(target.read_text())["branch"] == "S0"
    assert main(["series", "--nu", "2", "--out", str(tmp_path / "bad.txt")]) == 2
    assert not (tmp_path / "bad.txt").exists()
