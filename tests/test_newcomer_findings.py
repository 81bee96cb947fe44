"""Issue 34, findings 6 and 10 (and the count/n bound of finding 7): each as a user met it.

Every test here failed on the commit the issue was filed against (21ed01a): a traceback, a
wrong refusal, a message in the wrong words, a figure that hid what it should show.
"""
from __future__ import annotations

import json
import re
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from dispersion.cli import main

ROOT = Path(__file__).resolve().parents[1]


def _run(argv, capsys) -> tuple[int, str, str]:
    try:
        status = main(argv)
    except SystemExit as exc:
        status = exc.code
    except KeyboardInterrupt:  # a test failure, not an interrupt of the test session
        pytest.fail("Ctrl-C escaped dispersion.cli.main as a traceback")
    out = capsys.readouterr()
    return status, out.out, out.err.strip()


def _refused(argv, capsys) -> str:
    status, _, err = _run(argv, capsys)
    assert status == 2 and len(err.splitlines()) == 1, err
    assert "Traceback" not in err
    return err


# ---------------------------------------------------------------- finding 6

def test_an_element_size_beyond_the_floats_is_refused_not_a_traceback(capsys):
    # was: ZeroDivisionError (the consistent reference's step rounded to 0)
    err = _refused(["timestep", "--h", "1e-320"], capsys)
    assert "--h must lie in [1e-12, 1e+12] m" in err
    from dispersion.errors import InputError
    from dispersion.answers.critical_steps import critical_steps

    with pytest.raises(InputError, match=r"h must lie in \[1e-12, 1e\+12\]"):
        critical_steps(["lumped"], 1, model="bar", wave_speed=1.0, h=1e-320)


@pytest.mark.parametrize("option, lo, hi, text", [
    ("--courant", 0, 0.99, "0.99"), ("--courant", 0, 0.99, "99/100"),
    ("--x", 0.1, 0.3, "0.1"), ("--x", 0.1, 0.3, "0.3"), ("--x", 1e-12, 1e12, "1e-12"),
])
def test_the_end_of_a_range_written_as_a_decimal_is_inside_it(option, lo, hi, text):
    # was: "--courant must lie in (0, 0.99], got 0.99" (the float 0.99 is below 99/100)
    from dispersion.cli.options import real

    assert real(option, lo, hi)(text) == (0.99 if "/" in text else float(text))


def test_a_value_just_outside_a_range_is_not_shown_as_its_end():
    import argparse

    from dispersion.cli.options import real

    with pytest.raises(argparse.ArgumentTypeError, match=r"got 0\.99000001$"):
        real("--courant", 0, 0.99, lo_open=True)("0.99000001")


def test_an_indefinite_default_rule_is_skipped_with_a_line(monkeypatch, capsys):
    # was: `timestep --p 8` exit 2 with a raw IndefiniteMassWarning and an error about --mass,
    # which was not given (interpolatory-nodal is indefinite at p = 8; the slow test below)
    import dispersion.answers.critical_steps as cs
    from dispersion.mass_rules.mass_rule import user_rule

    negative = user_rule("negative-half", lambda s: -s.M / 2)   # states psd, is not
    monkeypatch.setattr(cs, "default_rules", lambda model: ("lumped", negative))
    status, out, err = _run(["timestep", "--p", "1", "--format", "csv"], capsys)
    assert status == 0, err
    assert err.splitlines() == [err.splitlines()[0]] and err.startswith(
        "skipped: mass negative-half: no critical step at p = 1"), err
    assert "Warning" not in err and "--mass" not in err
    rows = [ln for ln in out.splitlines() if not ln.startswith("#")]
    assert rows[1].startswith("lumped,") and len(rows) == 2
    assert "# skipped: mass negative-half" in out


def test_an_indefinite_rule_the_user_names_is_refused_in_words():
    import dispersion.answers.critical_steps as cs
    from dispersion.errors import InputError
    from dispersion.mass_rules.mass_rule import user_rule

    negative = user_rule("negative-half", lambda s: -s.M / 2)
    with pytest.raises(InputError, match="the mass rule 'negative-half' has no critical step"):
        cs.critical_steps([negative], 1)


@pytest.mark.slow
def test_timestep_at_p_8_keeps_every_rule_but_the_indefinite_one(capsys):
    status, out, err = _run(["timestep", "--p", "8", "--format", "csv"], capsys)
    assert status == 0, err
    assert err == ("skipped: mass interpolatory-nodal: no critical step at p = 8: it is "
                   "indefinite (smallest eigenvalue -0.00133) although it states psd")
    masses = [ln.split(",")[0] for ln in out.splitlines() if not ln.startswith("#")][1:]
    from dispersion.mass_rules.mass_rule import BLOCH_RULE_NAMES

    assert masses == [r for r in BLOCH_RULE_NAMES if r != "interpolatory-nodal"]


def test_an_over_long_output_name_is_refused_naming_the_option(tmp_path, monkeypatch, capsys):
    # was: exit 1, "File name too long", without --csv, after the work
    monkeypatch.chdir(tmp_path)
    err = _refused(["branches", "--exact", "--count", "3", "--csv", "a" * 252 + ".csv"],
                   capsys)
    assert err.startswith("dispersion branches: error: --csv: a name in the path is 256 bytes")
    assert list(tmp_path.iterdir()) == []


def test_a_refusal_writes_no_number_of_hundreds_of_digits():
    # was: `simulate --courant 1e-300`: "... x 3142801493794178766183761354893957..." (306 digits)
    from dispersion.simulation.run_cost import RequestTooLarge, RunCost, check_cost

    with pytest.raises(RequestTooLarge) as info:
        check_cost(RunCost(3232, 10**306, True), "simulation")
    assert "1.00e+306 steps = 3.23e+309 DOF-steps" in str(info.value)
    assert not re.search(r"\d{12}", str(info.value))


def test_ctrl_c_while_a_command_loads_is_one_line_and_130(monkeypatch, capsys):
    import dispersion.cli as cli

    def interrupted(name, package=None):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli.importlib, "import_module", interrupted)
    status, _, err = _run(["timestep"], capsys)
    assert (status, err) == (130, "dispersion: interrupted")


def test_ctrl_c_during_start_up_of_the_process_is_one_line():
    # a real SIGINT delivered while the command's parser is built (its modules import)
    code = ("import os, signal, sys\n"
            "import dispersion.cli as cli\n"
            "build = cli.build_parser\n"
            "def slow(*a, **k):\n"
            "    os.kill(os.getpid(), signal.SIGINT)\n"
            "    return build(*a, **k)\n"
            "cli.build_parser = slow\n"
            "sys.exit(cli.main(['timestep', '--mass', 'lumped']))\n")
    # a shell's background job inherits SIGINT ignored, and Python then installs no handler:
    # the child starts with the default disposition, as a terminal's foreground command does
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120, preexec_fn=_default_sigint)
    assert (proc.returncode, proc.stderr.strip()) == (130, "dispersion: interrupted")


def _default_sigint():
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def test_an_unknown_keyword_names_itself_and_the_accepted_ones():
    # was: a bare TypeError from the function the front door forwards to
    import dispersion
    from dispersion.errors import InputError, ParameterError

    for call in (lambda: dispersion.branch_table(exact_onyl=True),
                 lambda: dispersion.critical_steps(["lumped"], hh=1),
                 lambda: dispersion.lamb_modes("steel", 3.0, frequency=200),
                 lambda: dispersion.patch(mas="lumped")):
        with pytest.raises(ParameterError) as info:
            call()
        assert isinstance(info.value, InputError) and isinstance(info.value, TypeError)
        assert re.search(r"unknown keyword '\w+'; it accepts .*did you mean '\w+'\?$",
                         str(info.value)), str(info.value)
    readme = (ROOT / "README.md").read_text()
    assert "raises `ParameterError`, which is both an `InputError`" in readme


def test_one_mass_name_is_one_rule_and_no_rule_is_refused():
    # was: masses='lumped' read as the rules 'l', 'u', ...; masses=[] gave exact rows only
    import dispersion
    from dispersion.errors import InputError

    grid = dict(count=2, kappa_max=0.5, omega_max=1.0)
    for kw in ({"masses": "lumped"}, {"mass": "lumped"}, {"mass": ["lumped"]}):
        table = dispersion.branch_table(**kw, **grid)
        assert [d.name for d in table.discrete] == ["lumped"]
    for kw in ({"masses": []}, {"mass": ()}):
        with pytest.raises(InputError, match="at least one mass rule"):
            dispersion.branch_table(**kw, **grid)
    assert [s.mass for s in dispersion.critical_steps("lumped", 1, model="bar",
                                                      wave_speed=1.0).steps] == ["lumped"]


# ---------------------------------------------------------------- finding 10

def test_every_registered_rule_is_told_apart_in_one_figure():
    # was: consistent and interpolatory-nodal one blue, lumped and sms one orange
    import itertools

    from matplotlib.colors import to_rgb

    from dispersion.plotting.styles import mass_style
    from dispersion.mass_rules.mass_rule import RULE_NAMES

    styles = {r: mass_style(r) for r in RULE_NAMES}
    for a, b in itertools.combinations(RULE_NAMES, 2):
        assert to_rgb(styles[a].colour) != to_rgb(styles[b].colour), (a, b)
        assert styles[a].marker != styles[b].marker, (a, b)
    order = list(RULE_NAMES)
    assert all(styles[a].linestyle != styles[b].linestyle for a, b in zip(order, order[1:]))


@pytest.mark.parametrize("command, option", [
    (["timestep", "--mass", "sem-lumped"], "--model bar"),
    (["series", "--mass", "sem-lumped"], "--model x-exact"),
    (["branches", "--mass", "sem-lumped", "--count", "2"], "--model x-exact"),
])
def test_spectral_element_advice_is_an_option_of_the_command(command, option, capsys):
    # was: "use model='x-exact' or the periodic bar" (Python, and options timestep lacks)
    err = _refused(command, capsys)
    assert err.endswith(f": use {option}"), err
    assert "model='" not in err and "periodic bar" not in err


def test_spectral_element_advice_in_python_is_python():
    from dispersion.errors import InputError
    from dispersion.symbolic.patch import Patch

    with pytest.raises(InputError) as info:
        Patch(mass="sem-lumped")
    assert str(info.value).endswith("use model='x-exact'")
    assert "use model" not in info.value.reason   # what the strip's prediction writes


@pytest.mark.parametrize("key, meant", [("gamma-s", "gamma_s"), ("omega-max", "omega_max"),
                                        ("gama_s", "gamma_s")])
def test_verify_suggests_the_toml_key(key, meant, tmp_path, capsys):
    # was: "allowed: ..., --gamma-s, ..." (option names for the keys of a file), no suggestion
    path = tmp_path / "c.toml"
    path.write_text(f'[[claim]]\nname = "x"\nmodel = "patch"\nbranch = "A0"\n{key} = 0\n'
                    'series = "1*kappa^4"\n')
    err = _refused(["verify", str(path)], capsys)
    assert err.endswith(f"did you mean {meant!r}?") and "--" not in err.split("error:")[1]


def test_an_implausible_density_is_refused_naming_both_units(capsys):
    # was: a warning, then c_L = 195992 m/s and exit 0
    err = _refused(["branches", "--exact", "--youngs-modulus", "70", "--nu", "0.33", "--rho",
                    "2.7", "--thickness", "1", "--frequency", "200"], capsys)
    assert "--rho must lie in [100, 25000] kg/m^3" in err and "g/cm^3 given for kg/m^3" in err


def test_a_table_at_one_frequency_draws_its_points():
    # was: three empty panels (each mode one point, drawn as a line of no length)
    import dispersion

    fig = dispersion.figure(dispersion.lamb_modes("steel", 3.0, frequency_khz=200))
    for ax in fig.axes:
        points = [ln for ln in ax.get_lines() if len(ln.get_xdata()) == 1
                  and ln.get_marker() not in (None, "None", "")]
        assert len(points) == 3, ax.get_ylabel()


def test_a_bare_thickness_implausible_in_mm_is_hinted():
    # was: `simulate --thickness 0.003` ran without a word
    from dispersion.cli import build_parser
    from dispersion.cli.options import thickness_hints

    parser = build_parser("simulate")
    args = parser.parse_args(["simulate", "--thickness", "0.003"])
    thickness_hints(args)
    assert args.unit_hints == ["--thickness = 0.003 mm is implausibly small: metres given for "
                               "mm? (0.003 m = 3 mm); give the unit to be sure "
                               "(--thickness 0.003m)"]
    args = parser.parse_args(["simulate", "--thickness", "0.003m"])
    thickness_hints(args)
    assert args.thickness == 3.0 and not getattr(args, "unit_hints", None)


def test_simulate_is_in_the_top_level_help_and_the_readme(capsys):
    from dispersion.cli import _SUBCOMMANDS

    with pytest.raises(SystemExit):
        main(["--help"])
    helptext = " ".join(capsys.readouterr().out.split())
    assert f"dispersion {' | '.join(_SUBCOMMANDS)}." in helptext
    readme = " ".join((ROOT / "README.md").read_text().split())
    assert f"`dispersion {' | '.join(_SUBCOMMANDS)}`, and `dispersion --version`" in readme


@pytest.mark.parametrize("extra, first, absent", [
    (["--thickness", "0.003", "--frequency", "200"], "--thickness = 0.003 mm", "MHz"),
    (["--thickness", "3", "--frequency", "200Hz"], "--frequency must lie", "MHz given"),
])
def test_unit_hints_blame_what_is_wrong(extra, first, absent, capsys):
    # was: --frequency named first whatever was wrong; `200Hz` told "MHz given for kHz?"
    err = _refused(["branches", "--exact", "--material", "steel", *extra], capsys)
    assert err.split("error: ", 1)[1].startswith(first), err
    assert absent not in err
    if "200Hz" in extra:
        assert "write 200kHz" in err


@pytest.mark.parametrize("option, text, value", [
    ("--thickness", "10mm", 10.0), ("--thickness", "0.3cm", 3.0), ("--thickness", "0.003m", 3.0),
    ("--thickness", "3", 3.0), ("--h", "5mm", 0.005), ("--h", "1", 1.0), ("--h", "2 cm", 0.02),
])
def test_lengths_take_units(option, text, value):
    from dispersion.cli import build_parser

    command = "timestep" if option == "--h" else "simulate"
    args = build_parser(command).parse_args([command, option, text])
    assert getattr(args, option[2:]) == pytest.approx(value, rel=1e-15)


def test_lengths_and_frequencies_share_one_unit_parser():
    import inspect

    from dispersion.cli import options

    assert "split_unit(" in inspect.getsource(options._value)
    assert "split_unit(" in inspect.getsource(options.length)


def test_branch_table_documents_every_parameter_and_takes_the_cli_names():
    import inspect

    from dispersion.answers.branch_table import branch_table

    doc = inspect.getdoc(branch_table)
    documented = set()
    for line in doc.split("Parameters\n----------\n")[1].split("\n\nReturns")[0].splitlines():
        if line and not line.startswith(" "):
            documented |= {n.strip() for n in line.split(":")[0].split(",")}
    assert documented == set(inspect.signature(branch_table).parameters)
    assert {"mass", "exact", "masses", "exact_only"} <= documented


def test_every_result_writes_json_as_text(capsys):
    # was: to_json() returned a dict while to_csv(), to_text() returned text
    import dispersion

    results = [dispersion.branch_table(exact=True, count=2, kappa_max=1.0, omega_max=1.0),
               dispersion.lamb_modes("steel", 3.0, frequency_khz=200),
               dispersion.critical_steps(["lumped"], 1, model="bar", wave_speed=1.0)]
    for result in results:
        text = result.to_json()
        assert isinstance(text, str) and json.loads(text) == json.loads(
            json.dumps(result.to_dict(), allow_nan=False))


def test_the_main_job_says_each_section_as_it_finishes(monkeypatch, tmp_path, capsys):
    # was: nothing for minutes when stderr is not a terminal
    import types

    import dispersion.report.run as run

    monkeypatch.setattr(run, "section_module",
                        lambda name: types.SimpleNamespace(measure=lambda **kw: {"x": 1}))
    seconds = run.measure_sections(tmp_path, ["coefficients", "studies"], progress=False)
    err = capsys.readouterr().err.splitlines()
    assert [re.sub(r"[\d.]+ s", "S s", ln) for ln in err] == [
        "dispersion reproduce: measured coefficients in S s (1 of 2)",
        "dispersion reproduce: measured studies in S s (2 of 2)"]
    assert set(seconds) == {"coefficients", "studies"}


def test_the_readme_states_the_main_job_time_from_the_reports():
    from dispersion import results
    from dispersion.report import DEFAULT_SECTIONS

    total = sum(results.load(ROOT / "reports" / f"{n}.json")["seconds"]
                for n in DEFAULT_SECTIONS)
    readme = (ROOT / "README.md").read_text()
    assert f"The main job measured its sections in {total:.0f} s" in readme
    assert "<!-- generated from reports/*.json by" in readme


def test_a_change_of_partner_breaks_the_error_line():
    # was: drawn as a vertical line from one partner's error to the next one's
    import numpy as np

    from dispersion.plotting.branches import plot_paired_errors

    kappa = np.linspace(0.1, 1.0, 6)
    error = np.array([1e-3, 2e-3, 3e-3, -0.2, -0.3, -0.4])
    ax = plot_paired_errors(kappa, {"S1": error}, partners={"S1": [2, 2, 2, 3, 3, 3]}).axes[0]
    y = np.asarray(next(ln for ln in ax.get_lines() if ln.get_label() == "S1").get_ydata())
    assert np.isnan(y[3]) and np.isfinite(y).sum() == 6


def test_the_speed_accuracy_figure_labels_its_time_axis():
    from dispersion import results
    from dispersion.plotting.branches import figure_speed_accuracy

    data = results.load(ROOT / "reports" / "branches.json")["result"]
    fig = figure_speed_accuracy(data["tracer"], data["discrete_speed"])
    fig.canvas.draw()
    for ax in fig.axes:
        lo, hi = ax.get_xlim()
        labels = [t.get_text() for t in ax.get_xticklabels()
                  if t.get_text() and lo <= t.get_position()[0] <= hi]   # inside the axis
        assert len(labels) >= 2, labels
        boxes = [t.get_window_extent() for t in ax.get_xticklabels() if t.get_text()
                 and lo <= t.get_position()[0] <= hi]
        assert not any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1:])


def test_mode_labels_do_not_overprint():
    # was: 'SH1' over 'A1', 'S0' over 'S1' at the ends of the curves of 1 mm aluminium
    import numpy as np

    import dispersion

    grid = np.linspace(10.0, 3000.0, 60)
    fig = dispersion.figure(dispersion.lamb_modes("aluminium", 1.0, frequency_khz=grid))
    fig.canvas.draw()
    for ax in fig.axes:
        boxes = [t.get_window_extent() for t in ax.texts if t.get_text()[:1] in "SA"]
        assert not any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1:])


def test_an_oversized_simulation_is_refused_before_the_strip_is_assembled(monkeypatch):
    # was: refused after 20 s (the 1D bar's estimate fell short of the plate's step by up to
    # 17 times, so the true count was known only after the assembly and the Lanczos step)
    import math

    import scipy.sparse as sp

    import dispersion.simulation.strip_mesh as strip_mesh
    from dispersion.simulation.mass_operator import mass_operator
    from dispersion.simulation.mesh_critical_step import mesh_critical_step
    from dispersion.simulation.run_cost import RequestTooLarge
    from dispersion.simulation.strip import Strip, plan_strip
    from dispersion.simulation.wave_run import simulate
    from dispersion.time_stepping.timestep import matrix_critical_step

    strip = Strip(p=2, travel=1, stations=2, elements_per_wavelength=3)
    plan = plan_strip(strip)
    real = strip_mesh.strip_mesh
    mesh = real(plan)
    # the run's true cost: its own mesh's critical step, as simulate measures it
    steps = math.ceil(plan.t_end / (strip.courant
                                    * mesh_critical_step(mesh, mass_operator(mesh)).dt_crit))
    built = []
    monkeypatch.setattr(strip_mesh, "strip_mesh",
                        lambda plan: built.append(plan.n_elements_x) or real(plan))
    with pytest.raises(RequestTooLarge, match="about"):
        simulate(strip, cost_limit=mesh.n_dofs * steps - 1)   # just over the limit
    assert plan.n_elements_x not in built          # refused before the assembly
    # the short strip's largest frequency is the long one's (independent computation: the
    # dense generalized eigenproblem of the assembled strip, massless points condensed)
    from dispersion.simulation.run_cost import short_strip_omega

    dense = 2.0 / matrix_critical_step(mesh.K, sp.kron(mesh.mass, sp.identity(2)))
    assert short_strip_omega(plan) == pytest.approx(dense, rel=2e-3)


# ---------------------------------------------------------------- finding 7: count, n, bound

def test_a_costly_rule_at_a_high_degree_is_refused_before_work(monkeypatch, capsys):
    # was: `branches --mass dual-lumped --p 24 --n 25` ran for more than 15 minutes
    import dispersion.symbolic.plate as plate

    def no_work(*args, **kwargs):
        raise AssertionError("the patch was built before the bound was checked")

    monkeypatch.setattr(plate, "plate_patch", no_work)
    err = _refused(["branches", "--mass", "dual-lumped", "--p", "24", "--n", "25"], capsys)
    assert "mass rule 'dual-lumped' at p = 24" in err and "at most p = 16" in err
    err = _refused(["branches", "--mass", "dual-lumped", "--p", "10", "--n", "11"], capsys)
    assert "at most p = 8" in err and "n >= 13" in err


def test_every_n_the_command_accepts_runs_at_its_smallest_grid():
    # was: `branches --p 2 --n 200` could not run at all (--count 2 over the work bound,
    # --count 1 below the range); the range of --n is now the bound's
    from dispersion.answers.branch_table import DEFAULT_MASSES
    from dispersion.budget import (DISCRETE_N_MAX, DISCRETE_P_MAX, check_discrete_branches,
                                   discrete_n_max)
    from dispersion.cli import build_parser
    from dispersion.defaults import P_MAX
    from dispersion.errors import InputError
    from dispersion.mass_rules.mass_rule import BLOCH_RULE_NAMES

    n_action = next(a for a in build_parser("branches")._subparsers._group_actions[0]
                    .choices["branches"]._actions if "--n" in a.option_strings)
    assert n_action.type(str(DISCRETE_N_MAX)) == DISCRETE_N_MAX
    assert DISCRETE_N_MAX == max(discrete_n_max(p) for p in range(1, P_MAX + 1))
    for p in range(1, P_MAX + 1):
        assert discrete_n_max(p) >= max(p + 1, 3)      # every degree has an n that runs
        with pytest.raises(InputError, match=f"at most n = {discrete_n_max(p)} at this p"):
            check_discrete_branches(2, DEFAULT_MASSES, p, discrete_n_max(p) + 1)
        for n in range(max(p + 1, 3), discrete_n_max(p) + 1):
            check_discrete_branches(2, DEFAULT_MASSES, p, n)
            for rule in BLOCH_RULE_NAMES:
                bounds = DISCRETE_P_MAX.get(rule, {})
                if p <= bounds.get("patch", P_MAX) and (
                        n > 12 or p <= bounds.get("polynomial", P_MAX)):
                    check_discrete_branches(2, [rule], p, n)


@pytest.mark.parametrize("count, rules, p, n", [
    (400, 2, 2, 30), (2, 3, 2, 140), (200000, 1, 2, 10), (2, 12, 2, 100), (5, 1, 2, 140),
])
def test_every_refusal_of_the_bound_advises_values_the_command_accepts(count, rules, p, n):
    # was: `--n 100 --count 2` refused with "count <= 1", which the command rejects
    from dispersion.budget import check_discrete_branches, discrete_n_max
    from dispersion.errors import InputError

    with pytest.raises(InputError) as info:
        check_discrete_branches(count, ["consistent"] * rules, p, n)
    text = str(info.value)
    most_count = re.search(r"at most count = (\d+)", text)
    most_n = re.search(r"at most n = (\d+)", text)
    assert most_count or most_n, text
    if most_count:
        assert int(most_count.group(1)) >= 2
        check_discrete_branches(int(most_count.group(1)), ["consistent"] * rules, p, n)
    if most_n:
        assert p + 1 <= int(most_n.group(1)) <= discrete_n_max(p)
        check_discrete_branches(2, ["consistent"] * rules, p, int(most_n.group(1)))
