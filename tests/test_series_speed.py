"""Series speed study (``dispersion/studies/series_race.py``): parsers, fit, agreement, bounds, render.

No wall-clock assertions: only the bookkeeping and the coefficients are checked.
"""
from __future__ import annotations

import json
import math
import shutil
from fractions import Fraction

import pytest

from dispersion.studies import series_race as S
from dispersion.cli import main
from dispersion.errors import InputError

needs_maxima = pytest.mark.skipif(shutil.which("maxima") is None,
                                  reason="maxima not installed (apt-get install -y maxima)")


def test_parser_reads_maxima_lines():
    text = "N:2\nCOEF S0 2 -2/(nu-1)\nCOEF A0 4 -2/(3*(nu-1))\nTIME 0.25\n"
    coeffs, seconds = S.parse_maxima_output(text)
    assert seconds == 0.25 and coeffs == {"S0": {2: "-2/(nu-1)"}, "A0": {4: "-2/(3*(nu-1))"}}


def test_agreement_is_exact_and_can_fail():
    # eq 14's kappa^4 term in our syntax and in Maxima's; then a sign error must be caught
    ours = {"S0": {4: "2*nu**2/(3*(nu - 1)**3)"}}
    assert S._agree(ours, {"S0": {4: "(2*nu^2)/(3*(nu-1)^3)"}})
    assert not S._agree(ours, {"S0": {4: "-(2*nu^2)/(3*(nu-1)^3)"}})
    assert not S._agree(ours, {"S0": {}})
    assert S._value("-2/(nu-1)", Fraction(3, 10)) == Fraction(20, 7)  # eq 14: 2/(1 - nu)


def test_growth_fit_recovers_a_power_law_and_reports_the_misfit():
    ns = [3, 4, 6, 8, 12]
    exact = S.fit_growth(ns, [0.01 * n**2.5 for n in ns])
    assert math.isclose(exact["exponent"], 2.5, rel_tol=1e-9) and exact["residual"] < 1e-12
    noisy = S.fit_growth(ns, [0.01 * n**2.5 * (1.2 if i % 2 else 0.8) for i, n in enumerate(ns)])
    assert noisy["residual"] > 0.1
    with pytest.raises(InputError, match="at least 4 points"):
        S.fit_growth([3, 4, 5], [1, 2, 3])


def test_timeout_is_bounded():
    with pytest.raises(InputError, match=r"timeout .* must lie in \(0, 600\]"):
        S.measure(quick=True, timeout=1e308)


def test_cli_refuses_absurd_budget(capsys):
    assert main(["bench", "--budget", "1e308"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "budget" in err and "600" in err


def test_child_runner_reports_its_own_peak_memory():
    import sys

    small = S.run_child([sys.executable, "-c", "print(1)"], 30)
    big = S.run_child([sys.executable, "-c", "x = bytearray(200 * 2**20); print(len(x))"], 30)
    assert small[2].strip() == "1" and small[3] == 0
    assert big[1] > small[1] + 150  # MiB: the 200 MiB buffer, not the parent's peak


@pytest.mark.slow  # default-run budget: a process race, a fault run or a whole-package walk
@needs_maxima
def test_race_against_maxima_agrees_at_kappa_8():
    (point,) = S.race((8,), timeout=120)
    assert point.agree is True and point.maxima_status == "ok", point.maxima_error
    assert point.maxima_compute_s is not None and point.ours_process_s is not None


@pytest.mark.slow  # default-run budget: a process race, a fault run or a whole-package walk
def test_race_without_maxima_reports_ours_only():
    notes = []
    (point,) = S.race((4,), timeout=120, maxima=None, notes=notes)
    assert point.maxima_process_s is None and point.agree is None and point.ours_compute_s > 0


DATA = {
    "race": [{"order": 16, "ours_process_s": 0.5, "ours_compute_s": 0.01, "ours_peak_mib": 80.0,
              "ours_lean_process_s": 0.2, "maxima_process_s": 0.25, "maxima_compute_s": 0.04,
              "maxima_peak_mib": 60.0, "agree": True}],
    "scaling": [{"mass": m, "p": 2, "n": n, "order": 8, "seconds": s * n**3}
                for m, s in (("consistent", 1e-3), ("singular", 2e-3)) for n in (3, 4, 6, 8)],
    "fits": [{"mass": "consistent", "p": 2, "exponent": 3.0, "residual": 0.0,
              "monotone": True, "points": 4}],
    "maxima": "Maxima 5.x", "notes": [], "settings": {}}


def test_render_from_json_alone(tmp_path):
    pytest.importorskip("matplotlib")
    from dispersion.report.series_speed import render

    md = render(json.loads(json.dumps(DATA)), tmp_path)
    assert (tmp_path / "series_speed.png").stat().st_size > 0
    # whole process 0.25 / 0.5 = 0.5x (slower), compute 0.04 / 0.01 = 4x: both stated
    assert "kappa^16: 0.5x" in md and "kappa^16: 4x" in md and "Headline (whole process" in md
    assert "takes 2x (n = 8) the time of the consistent mass" in md


def test_readme_summary_quotes_the_data():
    from dispersion.report.series_speed import summary

    text = summary(json.loads(json.dumps(DATA)))
    # n = 8: 2e-3 * 512 = 1.02 s and 1e-3 * 512 = 0.512 s, as stored in DATA
    assert "ours 0.5 s" in text and "Maxima 0.25 s (Maxima/ours 0.5x)" in text
    assert "singular mass 1.02 s, consistent 0.512 s" in text and "consistent n^3.00" in text


# --- a peer run counts only if it succeeded (issue 18, item 5) ----------------------------

_STRINGPROC_ERROR = ("loadfile: failed to load /usr/share/maxima/share/stringproc/stringproc.lisp\n"
                     " -- an error. To debug this try: debugmode(true);\n")


def _stub_maxima(folder, body: str):
    """A fake ``maxima`` executable (first on PATH) that prints ``body`` and exits 0, as
    Debian's maxima without maxima-share does when the program cannot load stringproc."""
    exe = folder / "maxima"
    exe.write_text("#!/bin/sh\ncat <<'END'\n" + body + "END\nexit 0\n")
    exe.chmod(0o755)
    return exe


def test_peer_failure_names_each_way_a_peer_can_fail():
    ours = {"S0": {2: "-2/(nu - 1)"}}
    good = {"S0": {2: "-2/(nu-1)"}}
    assert S.peer_failure(0, "COEF S0 2 -2/(nu-1)\nTIME 0.01\n", "", good, ours) is None
    assert S.peer_failure(1, "", "Segmentation fault", good, ours).startswith("exit status 1")
    assert "printed an error" in S.peer_failure(0, _STRINGPROC_ERROR, "", good, ours)
    assert S.peer_failure(0, "TIME 0.01\n", "", {}, ours).startswith("returned no coefficients")
    assert "differ" in S.peer_failure(0, "", "", {"S0": {2: "2/(nu-1)"}}, ours)
    assert "differ" in S.peer_failure(0, "", "", {"S0": {2: "-2/(nu-1)", 4: "1"}}, ours)


@pytest.mark.slow  # default-run budget: a process race, a fault run or a whole-package walk
def test_a_failing_peer_is_reported_and_not_timed(tmp_path):
    stub = _stub_maxima(tmp_path, _STRINGPROC_ERROR + "TIME 0.01\n")
    notes = []
    (point,) = S.race((4,), timeout=120, maxima=str(stub), notes=notes)
    assert point.maxima_status == "failed" and "stringproc" in point.maxima_error
    assert point.maxima_process_s is None and point.maxima_compute_s is None
    assert point.maxima_peak_mib is None and point.ours_process_s is not None
    assert any("not timed" in n for n in notes)


@pytest.mark.slow  # a whole bench --quick (four child runs); the race-level test above is
# the default run's check that a failing peer is not timed
def test_bench_with_a_failing_maxima_prints_no_ratio(tmp_path, monkeypatch, capsys):
    stub = _stub_maxima(tmp_path, _STRINGPROC_ERROR)
    monkeypatch.setenv("PATH", f"{stub.parent}:{__import__('os').environ['PATH']}")
    # the scaling table is not what this test is about: keep it out (it costs seconds)
    monkeypatch.setattr(S, "scaling", lambda grid, **kw: ((), ()))
    assert main(["bench", "--quick", "--format", "text"]) == 0
    text = capsys.readouterr().out
    assert "Maxima failed" in text and "stringproc" in text
    table = [ln for ln in text.splitlines() if ln.startswith("| 8 |") or ln.startswith("| 16 |")]
    assert len(table) == 2
    for row in table:
        cells = [c.strip() for c in row.strip("|").split("|")]
        # Maxima process s, Maxima/ours, Maxima compute s, its ratio: all empty; verdict FAILED
        assert cells[2] == cells[3] == cells[6] == cells[7] == "-" and cells[-1] == "FAILED"
    assert "Maxima/ours is" not in text and "x;" not in text


@pytest.mark.slow  # one Maxima process (about 1 s); the default run races it at kappa^8
@needs_maxima
def test_peer_program_returns_the_closed_form_coefficients():
    # runs the shipped Maxima program once (kappa^4): eq 14's leading S0 term is the plate
    # velocity squared, (c_plate / c_T)^2 = 2 / (1 - nu) (closed form); A0 starts at kappa^4
    # with 2 / (3 (1 - nu)) (Kirchhoff plate, D / (rho h) in units of c_T and half-thickness)
    import subprocess

    with S._batch_file(4, S.maxima_program()) as (folder, name):
        proc = subprocess.run(["maxima", "--very-quiet", "-b", name], cwd=folder, text=True,
                              capture_output=True, timeout=120, check=False)
    coeffs, seconds = S.parse_maxima_output(proc.stdout)
    assert S.peer_failure(proc.returncode, proc.stdout, proc.stderr, coeffs,
                          S._ours_compute(4)[1]) is None, proc.stdout[-500:]
    nu = Fraction(3, 10)
    assert S._value(coeffs["S0"][2], nu) == 2 / (1 - nu)
    assert S._value(coeffs["A0"][4], nu) == Fraction(2, 3) / (1 - nu)
    assert seconds is not None


def test_scaling_labels_state_the_patch_its_points_stored(tmp_path):
    # issue 22: "Bloch r = 2" was typed in the figure title and the page; the points now store
    # their patch, and the labels come from it (r = 5/2, contact bottom, gamma_s = 1/3: values
    # no code path types)
    pytest.importorskip("matplotlib")
    from dispersion.report.series_speed import _scaling_patch, render, summary
    from dispersion.symbolic.patch import Patch

    data = json.loads(json.dumps(DATA))
    for q in data["scaling"]:
        q["patch"] = Patch(p=q["p"], n=q["n"], mass=q["mass"], r="5/2", contact="bottom",
                           gamma_s="1/3").as_dict()
    want = "Bloch r = b/h = 5/2; singular: contact bottom, gamma_s = 1/3"
    assert _scaling_patch(data["scaling"]) == want
    md = render(data, tmp_path)
    assert want in md and "r = 2" not in md
    assert want in summary(data)
    point = S.scaling({2: (3,)}, masses=("singular",), order=4)[0][0]
    assert Patch.from_dict(point.patch) == Patch(mass="singular")
