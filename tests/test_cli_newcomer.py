"""The newcomer defects of issue 28, each as a new user met it (each failed before the fix).

A calculator on a terminal prints an aligned, rounded table; headers are words with units;
errors name the option, the unit and the likely mix-up; names are case-insensitive and a
near miss gets a did-you-mean; usage errors answer before the heavy imports.
"""
from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest

from dispersion.cli import main

CALCULATOR = ["branches", "--exact", "--material", "steel", "--thickness", "3",
              "--frequency", "200"]


def _err(argv, capsys) -> str:
    try:
        status = main(argv)
    except SystemExit as exc:
        status = exc.code
    err = capsys.readouterr().err.strip()
    assert status == 2 and len(err.splitlines()) == 1, err
    return err


def test_the_headline_question_prints_an_aligned_table_on_a_terminal(capsys, monkeypatch):
    monkeypatch.setattr(sys.stdout, "isatty", lambda: True)
    assert main(CALCULATOR) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0] == "steel, d = 3 mm, nu = 0.2912" and not out[0].startswith("#")
    head = out.index(next(ln for ln in out if ln.startswith("f [kHz]")))
    table = out[head:head + 5]
    assert re.fullmatch(r"[- ]+", table[1]) and table[2].split()[1] == "S0"
    assert "5414.646" in table[2] and "5414.646094" not in table[2]   # rounded, 7 digits
    assert len(table[1]) == len(table[0])                             # aligned


def test_piped_output_is_csv(capsys, monkeypatch):
    monkeypatch.setattr(sys.stdout, "isatty", lambda: False)
    assert main(CALCULATOR) == 0
    out = capsys.readouterr().out
    assert out.startswith("# steel, d = 3 mm") and "5414.646094137197" in out


@pytest.mark.parametrize("argv", [
    ["branches", "--count", "3", "--kappa-max", "1", "--omega-max", "2", "--format", "csv"],
    ["branches", "--exact", "--material", "aluminium", "--thickness", "1", "--count", "3",
     "--format", "csv"],
    [*CALCULATOR, "--format", "csv"], [*CALCULATOR, "--mode-shape", "A0", "--format", "csv"],
    ["series", "--exact", "--order", "4", "--format", "csv"],
    ["timestep", "--mass", "lumped", "--format", "csv"],
])
def test_csv_headers_are_words_with_units(argv, capsys):
    assert main(argv) == 0
    header = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("#")]
    assert len(header) >= 3
    for line in header:  # no Python reprs of dicts, lists, numpy scalars
        assert not re.search(r"\{'|\['|np\.|array\(", line), line


def test_the_mode_shape_csv_lists_its_own_columns(capsys):
    assert main([*CALCULATOR, "--mode-shape", "A0", "--format", "csv"]) == 0
    lines = capsys.readouterr().out.splitlines()
    columns = next(ln for ln in lines if not ln.startswith("#"))
    assert columns == "f [kHz],k [rad/mm],y [mm],u_x,u_y,sigma_xx,sigma_yy,sigma_xy"
    assert not any("c_p [m/s]" in ln for ln in lines)  # not the mode table's


@pytest.mark.parametrize("extra, words", [
    (["--thickness", "0.003"], ("--thickness = 0.003 mm", "metres given for mm", "--frequency")),
    (["--frequency", "200000"], ("--frequency", "Hz given for kHz", "200000Hz")),
])
def test_errors_name_the_option_the_unit_and_the_mixup(extra, words, capsys):
    err = _err([*CALCULATOR, *extra], capsys)
    assert all(w in err for w in words), err
    assert "np.float64" not in err and "frequency_khz" not in err and "thickness_mm" not in err


@pytest.mark.parametrize("material, words", [
    (["--cl", "5.96", "--ct", "3.235"], ("--cl = 5.96 m/s", "km/s given for m/s")),
    (["--youngs-modulus", "200e9", "--nu", "0.3", "--rho", "7850"],
     ("--youngs-modulus = 2e+11 GPa", "Pa given for GPa")),
])
def test_user_material_mixups_are_named(material, words, capsys):
    err = _err(["branches", "--exact", "--thickness", "3", "--frequency", "200", *material],
               capsys)
    assert all(w in err for w in words), err


@pytest.mark.parametrize("argv, hint", [
    (["series", "--mass", "singlar"], "did you mean 'singular'?"),
    (["branches", "--mass", "consistant"], "did you mean 'consistent'?"),
    (["branches", "--exact", "--material", "stell", "--thickness", "1"], "did you mean 'steel'?"),
    (["timestep", "--model", "bra"], "did you mean 'bar'?"),
    (["ring", "--scheme", "kain"], "did you mean 'kane'?"),
    ([*CALCULATOR, "--mode-shape", "A9"], "one of the modes propagating"),
])
def test_names_get_a_did_you_mean(argv, hint, capsys):
    assert hint in _err(argv, capsys)


def test_material_and_mode_names_ignore_case(capsys):
    argv = ["branches", "--exact", "--material", "Steel", "--thickness", "3", "--frequency",
            "200", "--mode-shape", "a0", "--format", "json"]
    assert main(argv) == 0
    assert json.loads(capsys.readouterr().out)["title"].startswith("A0 mode shape, steel")


_HEAVY = """
import json, runpy, sys
sys.argv = ["dispersion", *sys.argv[1:]]
try:
    runpy.run_module("dispersion", run_name="__main__")
except SystemExit:
    pass
print(json.dumps(sorted({m.split(".")[0] for m in sys.modules}
                        & {"numpy", "sympy", "scipy", "matplotlib", "mpmath", "flint",
                           "pandas"})))
"""


@pytest.mark.parametrize("argv", [
    ["branches", "--mass", "singlar"], ["series", "--mass", "singlar"],
    ["branches", "--exact", "--count", "1e9"], ["timestep", "--model", "plates"],
    ["branches", "--exact", "--frequency", "100:200:1", "--material", "steel",
     "--thickness", "3"], ["ring", "--level", "7"], ["verify"],
])
def test_usage_errors_answer_before_the_heavy_imports(argv):
    # the measure of start-up cost is benchmarks/bench_calculator.py; here what is imported
    proc = subprocess.run([sys.executable, "-c", _HEAVY, *argv], capture_output=True,
                          text=True, timeout=120)
    assert json.loads(proc.stdout.strip().splitlines()[-1]) == [], proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1


def test_the_calculator_imports_no_sympy():
    proc = subprocess.run([sys.executable, "-c", _HEAVY, *CALCULATOR], capture_output=True,
                          text=True, timeout=120)
    assert not {"sympy", "scipy", "matplotlib"} & set(json.loads(proc.stdout.splitlines()[-1]))
    code = "import dispersion, sys; dispersion.lamb_modes('steel', 3.0, frequency_khz=200); " \
           "print('sympy' in sys.modules)"
    assert subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120).stdout.strip() == "False"


def test_the_readme_shows_what_the_calculator_prints(capsys, monkeypatch):
    # issue 28 "done means": the README's calculator example prints the aligned table; the
    # block under the command is that output, checked here (never typed by hand)
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text()
    block = readme.split("(tests/test_cli_newcomer.py checks it) -->\n```text\n", 1)[1]
    block = block.split("```", 1)[0]
    monkeypatch.setattr(sys.stdout, "isatty", lambda: True)
    assert main(CALCULATOR) == 0
    assert capsys.readouterr().out.startswith(block)


@pytest.mark.slow  # 400 kappa of two masses, paired by shape, and a PNG
def test_the_readme_figure_2_command_draws_figure_2(tmp_path, monkeypatch, capsys):
    # issue 26 item 7: the README's "Figure 2" command gives the paper's Figure 2 (r = 1/2),
    # and says so in what it writes (rendered from the result)
    import shlex
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text()
    line = next(ln for ln in readme.splitlines() if "# the paper's Figure 2" in ln)
    args = shlex.split(line.split("#")[0])[1:]
    monkeypatch.chdir(tmp_path)
    assert main([*args, "--count", "20"]) == 0
    header = (tmp_path / "branches.csv").read_text()
    assert "# patch: Bloch r = b/h = 1/2, p = 2, n = 3" in header
    assert (tmp_path / "fig2.png").stat().st_size > 10_000


def test_the_physical_figure_draws_the_discrete_branches():
    # issue 26 item 6: with a material the discrete branches were computed, written to the
    # CSV, and left out of the figure (byte-identical to the --exact one)
    from dispersion.api import branch_table, figure

    request = dict(material="steel", thickness_mm=3.0, count=40)
    with_discrete = figure(branch_table(masses=["consistent", "lumped"], **request))
    exact = figure(branch_table(exact_only=True, **request))

    def markers(fig):
        return sum(1 for ax in fig.axes for ln in ax.get_lines()
                   if ln.get_marker() not in (None, "None", "", " ") and len(ln.get_xdata()) > 2)
    assert markers(exact) == 0
    assert markers(with_discrete) >= 2 * 3  # both masses in each of the three panels
    labels = [t.get_text() for t in with_discrete.legends[0].get_texts()]
    assert any(lab.startswith("consistent") for lab in labels)
    assert any(lab.startswith("lumped") for lab in labels)
