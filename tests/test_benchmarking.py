"""Plumbing of the series benchmark (``dispersion/benchmarking.py``): parsers, routes, budget.

No wall-clock assertions: only the coefficients and the bookkeeping are checked.
"""
from __future__ import annotations

import shutil
import time

import pytest
import sympy

from dispersion import benchmarking as B
from dispersion.cli import main
from dispersion.power_balance import discrete_series, exact_series

nu = B.NU

# Paper eqs (14)-(15) (Amirkulova 2011), the exact long-wave Rayleigh-Lamb series.
EQ14 = {2: 2 / (1 - nu), 4: -2 * nu**2 / (3 * (1 - nu) ** 3),
        6: 2 * nu**2 * (7 * nu**2 + 10 * nu - 6) / (45 * (1 - nu) ** 5)}
EQ15 = {4: 2 / (3 * (1 - nu)), 6: 2 * (7 * nu - 17) / (45 * (1 - nu) ** 2)}

needs_maxima = pytest.mark.skipif(shutil.which("maxima") is None,
                                  reason="maxima not installed (apt-get install -y maxima)")


def same(a, b) -> bool:
    return sympy.cancel(sympy.sympify(a) - b) == 0


def test_parser_reads_maxima_linear_syntax():
    # Hand-written lines in the format the .mac program prints; the values are eq 14's
    # kappa^2 and kappa^4 terms written the way Maxima's string() writes them.
    text = ("N:2\nbatchload(\"x\")\ntaylor: assumed to be zero: t^9\n"
            "COEF S0 2 -2/(nu-1)\nCOEF S0 4 (2*nu^2)/(3*(nu-1)^3)\n"
            "COEF A0 4 -2/(3*(nu-1))\nTIME 0.25\n")
    coeffs, seconds = B.parse_maxima_output(text)
    assert seconds == 0.25
    assert set(coeffs) == {"S0", "A0"} and sorted(coeffs["S0"]) == [2, 4]
    assert same(coeffs["S0"][2], EQ14[2]) and same(coeffs["S0"][4], EQ14[4])
    assert same(coeffs["A0"][4], EQ15[4])


@needs_maxima
def test_maxima_run_matches_eqs_14_15_and_our_engine():
    res = B.run_maxima(8)
    assert res.complete, res.note
    assert sorted(res.coefficients["S0"]) == [2, 4, 6, 8]
    assert sorted(res.coefficients["A0"]) == [4, 6, 8]
    for power, value in EQ14.items():
        assert same(res.coefficients["S0"][power], value)
    for power, value in EQ15.items():
        assert same(res.coefficients["A0"][power], value)
    # kappa^8 has no printed reference: the independent route is our own engine.
    ours = {b: exact_series(b, 8) for b in ("S0", "A0")}
    count, bad = B.compare(ours, res.coefficients)
    assert count == 7 and bad == []


def test_missing_maxima_is_reported_not_raised():
    res = B.run_maxima(4, executable="no-such-maxima-binary")
    assert res.seconds is None and not res.complete and "not found" in res.note


def test_textbook_rayleigh_lamb_agrees_with_engine_and_eqs_14_15():
    # Plain sympy series + solve on cos(sqrt z), sin(sqrt z)/sqrt z: an independent route.
    s0 = dict(B.textbook_orders(B.textbook_rayleigh_lamb("S0"), 1, 4))
    a0 = dict(B.textbook_orders(B.textbook_rayleigh_lamb("A0"), 2, 4))
    assert same(s0[2], EQ14[2]) and same(s0[4], EQ14[4]) and same(a0[4], EQ15[4])
    ours = {"S0": exact_series("S0", 4), "A0": exact_series("A0", 4)}
    count, bad = B.compare(ours, {"S0": s0, "A0": a0})
    assert count == 3 and bad == []


def test_textbook_determinant_agrees_with_engine_kappa2_kappa4():
    # Matrix.det of the full 6x6 x-exact K_dyn at nu = 1/4 (symbolic nu costs minutes),
    # series + solve, against the engine's discrete series at the same nu.
    nu_val = sympy.Rational(1, 4)
    F = B.textbook_plate("consistent", "x-exact", nu=nu_val)
    for branch, sigma in (("S0", 1), ("A0", 2)):
        textbook = dict(B.textbook_orders(F, sigma, 4))
        ours = discrete_series(branch, 4, model="x-exact", nu=nu_val)
        assert set(textbook) == set(ours) == set(range(2 * sigma, 5, 2))
        for power, value in textbook.items():
            assert same(value, ours[power]), (branch, power)
    # The leading S0 term is the plate velocity, eq 14's 2/(1 - nu), for any discretisation.
    assert same(dict(B.textbook_orders(F, 1, 2))[2], EQ14[2].subs(nu, nu_val))


def test_textbook_budget_keeps_finished_orders_and_marks_the_rest():
    def slow_build():  # the S0 equation of the bar-like toy F = W (W - 2 kappa^2), then a stall
        return B._W * (B._W - 2 * B.KAPPA**2)

    res = B.run_textbook(slow_build, ("S0",), 4, budget=30.0)
    assert res.complete and res.coefficients["S0"] == {2: 2, 4: 0}

    def stall():
        time.sleep(30)
        return B._W

    res = B.run_textbook(stall, ("S0",), 4, budget=0.5)
    assert not res.complete and res.seconds == 0.5 and res.coefficients == {"S0": {}}
    assert "budget" in res.note


def test_compare_reports_a_wrong_coefficient():
    count, bad = B.compare({"S0": {2: EQ14[2], 4: EQ14[4]}},
                           {"S0": {2: EQ14[2], 4: -EQ14[4]}, "A0": {4: EQ15[4]}})
    assert count == 2 and len(bad) == 1 and "kappa^4" in bad[0]


def test_table_marks_stopped_baselines_with_greater_than():
    ours = B.RouteResult("ours", {"S0": {2: EQ14[2]}}, 0.5)
    slow = B.RouteResult("textbook", {"S0": {}}, 10.0, complete=False, note="stopped")
    result = B.BenchmarkResult([B.Row("toy", {"ours": ours, "textbook": slow})], 1.0, 1.0, None,
                               {})
    table = B.format_table(result)
    assert "| toy | 0.5 | - | > 10 | > 20 |" in table


def test_cli_rejects_bad_budget(capsys):
    assert main(["bench", "--budget", "-1"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "budget" in err


@pytest.mark.slow
def test_series_speed_report_writes_chart_and_data(tmp_path):
    pytest.importorskip("matplotlib")
    from dispersion.report.series_speed import report

    md = report(tmp_path, quick=True)
    assert (tmp_path / "series_speed.png").stat().st_size > 0
    import json

    data = json.loads((tmp_path / "series_speed.json").read_text())
    assert [k for k, _ in data["rayleigh_lamb"]["ours"]] == [4, 8]
    assert "series_speed.png" in md and "series_speed.json" in md
