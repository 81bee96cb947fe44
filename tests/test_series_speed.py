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


@needs_maxima
def test_race_against_maxima_agrees_at_kappa_8():
    (point,) = S.race((8,), timeout=120)
    assert point.agree is True
    assert point.maxima_compute_s is not None and point.ours_process_s is not None


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
