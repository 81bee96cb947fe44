"""Every request is bounded before work, and every failure is one line (issue 17, items 2 and 6).

The refusals are checked to come before the work: the function that would do the work is
replaced by one that fails the test if it is reached.
"""
from __future__ import annotations

import re

import pytest

from dispersion.cli import main
from dispersion.errors import InputError


def _one_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    return err[0]


def _never(*args, **kwargs):
    raise AssertionError("the work started")


@pytest.mark.parametrize("args", [
    ["reproduce", "--out", ""], ["ring", "--out", ""], ["impact", "signorini-1d", "--out", ""],
    ["branches", "--csv", ""], ["branches", "--figure", ""], ["verify", "--paper", "--junit", ""],
    ["series", "--json", ""], ["bench", "--out", ""]])
def test_empty_output_path_is_refused_everywhere(args, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(args) == 2
    assert "''" in _one_line(capsys)
    assert list(tmp_path.iterdir()) == []


def test_impact_elements_times_steps_bounded_before_work(monkeypatch, capsys):
    import dispersion.contact.signorini as sig

    monkeypatch.setattr(sig, "assemble_bar", _never)
    assert main(["impact", "signorini-1d", "--elements", "100000", "--t-end", "0.002"]) == 2
    assert "min, more than the bound" in _one_line(capsys)
    assert main(["impact", "signorini-1d", "--elements", "100000"]) == 2  # memory first
    assert "GiB" in _one_line(capsys)
    # the rule's numbers: the default scene is far inside, 2000 elements at p = 6 is not
    assert sig.work_seconds(1, 20, 6000) < 5
    assert sig.work_seconds(6, 2000, 1) > sig.MAX_SECONDS


def test_impact_tiny_step_is_one_line(capsys):
    assert main(["impact", "signorini-1d", "--dt", "1e-300", "--t-end", "1e-299"]) == 2
    assert "dt must be >= 1e-150" in _one_line(capsys)


@pytest.mark.parametrize("args", [["--xi-elements", "4096", "--eta-elements", "2"],
                                  ["--level", "4", "--t-end", "900"]])
def test_ring_work_bounded_before_work(args, monkeypatch, capsys):
    import dispersion.contact.simulate as simulate

    monkeypatch.setattr(simulate, "ring_problem", _never)
    assert main(["ring", *args]) == 2
    assert "min, more than the bound of 30 min" in _one_line(capsys)


def test_ring_work_estimate_admits_the_default_scene():
    from dispersion.contact.scenario import MAX_SECONDS, Scenario

    assert Scenario().work_seconds < MAX_SECONDS / 10
    assert Scenario().with_level(3).work_seconds < MAX_SECONDS
    assert Scenario().with_level(4).work_seconds > MAX_SECONDS


def test_exact_signorini_time_bounded_up_front():
    from dispersion.contact.signorini import MAX_T_EXACT, exact_solution

    with pytest.raises(InputError, match="t_max must be <= "):
        exact_solution(1e12)
    with pytest.raises(InputError, match="t_max"):
        exact_solution(float("nan"))
    ex = exact_solution(3000.0)  # linear in the pieces: quick well inside the bound
    assert len(ex.a_knots) < MAX_T_EXACT


@pytest.mark.parametrize("args, code, word", [
    (["--r-outer", "1e300"], 2, "non-finite|leave double precision"),
    (["--v0", "1e12"], 1, "ConvergenceError")])
def test_ring_scale_failures_are_one_line_without_warnings(args, code, word, capsys):
    # pytest turns RuntimeWarnings into errors (pyproject): none may escape the integrator
    assert main(["ring", "--t-end", "0.1", *args]) == code
    assert re.search(word, _one_line(capsys))


def test_k_dyn_of_nan_is_an_input_error():
    import dispersion

    for bad in (float("nan"), float("inf"), "1", 1j):
        with pytest.raises(InputError, match="kappa must be a finite real number"):
            dispersion.patch().K_dyn(kappa=bad)
    with pytest.raises(InputError, match="Omega"):
        dispersion.patch().K_dyn(Omega=float("nan"))


@pytest.mark.parametrize("args, word", [
    (["--v0", "1e300"], "E = 2 (1 + nu) rho"), (["--v0", "1e-300"], "E = 2 (1 + nu) rho"),
    (["--dt", "1e300"], "dt must lie in"), (["--dt", "1e-200"], "dt must lie in")])
def test_ring_values_beyond_double_precision_are_refused(args, word, capsys):
    # counterexamples the slow CLI fuzz found (OverflowError tracebacks before the fix)
    assert main(["ring", "--t-end", "0.1", *args]) == 2
    assert word in _one_line(capsys)


def test_impact_before_the_first_contact_states_no_nan(capsys):
    # the exact contact stress is 0 until t = 1 (exact solution by characteristics): its
    # relative error is undefined and is stated so (null in JSON), never a silent NaN
    import json

    assert main(["impact", "signorini-1d", "--t-end", "0.1", "--format", "json"]) == 0
    summary = json.loads(capsys.readouterr().out)["summary"]
    assert summary["stress_rel_l2"] is None and summary["u0_rel_l2"] > 0
    assert main(["impact", "signorini-1d", "--t-end", "0.1"]) == 0
    out = capsys.readouterr().out
    assert "contact stress n/a (exact value 0)" in out and "nan" not in out


def test_branches_at_the_smallest_kappa_prints_no_numpy_warning(capsys):
    # a counterexample of the slow CLI fuzz: the complex step h = 1e-30 kappa underflows at
    # kappa = 1e-300 (pytest turns the RuntimeWarning into an error, pyproject)
    assert main(["branches", "--exact", "--count", "2", "--omega-max", "2",
                 "--kappa-max", "1e-300"]) == 0
    assert "RuntimeWarning" not in capsys.readouterr().err
