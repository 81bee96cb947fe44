"""Every result a user can get renders itself (issue 28 item 2): title, inputs in words, rows,
failures in every format, strict JSON, a DataFrame, a short repr and HTML.

The result types are enumerated twice: every subclass of
:class:`dispersion.rendering.Rendered` in the package (found by importing every module), and
every function of the front door and of the commands that returns a result; each type has a
small instance built here, and the test fails when a type has none (a new result type must
come with one).
"""
from __future__ import annotations

import dataclasses
import importlib
import json
import pkgutil
import re

import pytest

import dispersion
from dispersion.rendering import FORMATS, Rendered, failure_lines, render

#: What a header or title must never show: Python reprs of containers, numpy scalars, objects.
REPR = re.compile(r"\{'|\['|np\.float|np\.int|array\(|<[\w.]+ object at|Fraction\(|Rational\(")


def _all_result_types() -> set[type]:
    for info in pkgutil.walk_packages(dispersion.__path__, "dispersion."):
        if info.name.endswith("__main__"):
            continue
        importlib.import_module(info.name)
    out, todo = set(), [Rendered]
    while todo:
        for sub in todo.pop().__subclasses__():
            todo.append(sub)
            if sub.__module__.startswith("dispersion.") and sub.__name__ != "BranchViews":
                out.add(sub)
    return out


def _branch_table():
    from dispersion.answers.branch_table import branch_table

    t = branch_table(masses=["lumped"], kappa_max=1.0, count=3, omega_max=3.0,
                     material="aluminium", thickness_mm=1.0)
    return dataclasses.replace(t, failures=("exact S branches at kappa = 0.5: a planted failure",))


def _mode_table():
    t = dispersion.lamb_modes("steel", 3.0, frequency_khz=[200.0, 1000.0])
    roots = dataclasses.replace(t.roots, failures=((float(t.roots.omega[0]), "S", "planted"),))
    return dataclasses.replace(t, roots=roots)


def _mode_shapes():
    from dispersion.answers.mode_shape_table import mode_shapes

    return mode_shapes(dispersion.lamb_modes("titanium", 2.0, frequency_khz=1000.0), "A1", 9)


def _exact():
    from dispersion.continuum.exact_branches import trace_branches

    e = trace_branches(0.3, [0.0, 0.5, 1.0], 3.0)
    return dataclasses.replace(e, failures=[("S", 0.5, "a planted failure")])


def _velocities():
    from dispersion.continuum.velocities import exact_velocities

    v = exact_velocities(_exact())
    return dataclasses.replace(v, uncertain=(("A1", 1.0, "a planted failure"),))


def _discrete():
    return dispersion.patch(mass="lumped").branches([0.0, 0.5, 1.0], 0.3, group=True)


def _series():
    from dispersion.answers.series_table import series_table

    return series_table(("S0", "A0"), 6, exact=True, nu="3/10")


def _errata():
    from dispersion.claims.errata_sheet import errata_sheet

    return errata_sheet(equations=("17",))


def _steps():
    from dispersion.answers.critical_steps import critical_steps

    return critical_steps(["consistent", "lumped"], 2, model="bar")


def _step():
    from dispersion.time_stepping.timestep import critical_step

    return critical_step("hrz", 1, model="bar", wave_speed=1.0)


def _ring():
    r = dispersion.simulate_ring("lumped", t_end=0.2, dt=0.05)
    return dataclasses.replace(r, summary=dict(r.summary, energy_flag="a planted flag"))


def _signorini():
    from dispersion.contact.signorini import signorini_1d

    return signorini_1d(p=1, n_elements=8, mass="lumped", dt=0.05, t_end=0.5)


def _bar():
    return dispersion.simulate_bar(6, 2, "lumped", t_end_factor=0.5)


def _verification():
    from dispersion.claims import parse_claims, verify_claims

    return verify_claims(parse_claims('[[claim]]\nname = "eq 15, mistyped"\nmodel = '
                                      '"rayleigh-lamb"\nbranch = "A0"\nseries = '
                                      '"2/(3*(1-nu))*kappa^4 + 2*(7*nu - 71)/(45*(1-nu)^2)'
                                      '*kappa^6"\n'))


def _wave_run():
    from dispersion.simulation.wave_run import Strip, simulate

    return simulate(Strip(p=1, travel=1, stations=2, elements_per_wavelength=3, kappa_c=1.0))


def _layered():
    t = dispersion.layered_lamb_modes("steel:0.5,copper:0.5", frequency_khz=[300.0])
    return dataclasses.replace(t, roots=dataclasses.replace(
        t.roots, failures=((0.3, "L", "a planted failure"),)))


def _evanescent():
    t = dispersion.evanescent_modes("steel:1", frequency_khz=[300.0], decay_db=20.0,
                                    families=("A",))
    return dataclasses.replace(t, roots=dataclasses.replace(
        t.roots, failures=((0.3, "A", "a planted failure"),)))


def _slowness():
    t = dispersion.slowness_curves("steel:0.5,copper:0.5", 300.0, [0.0, 45.0])
    planted = dataclasses.replace(t.roots[0], failures=((0.3, "L", "a planted failure"),))
    return dataclasses.replace(t, roots=(planted, *t.roots[1:]))


#: One small instance of every result type (its name -> a function building it).
INSTANCES = {"BranchTable": _branch_table, "ModeTable": _mode_table,
             "LayeredModeTable": _layered, "SlownessTable": _slowness,
             "EvanescentModeTable": _evanescent,
             "ModeShapeTable": _mode_shapes, "ExactBranches": _exact,
             "Velocities": _velocities, "DiscreteBranches": _discrete, "SeriesTable": _series,
             "ErrataSheet": _errata, "CriticalSteps": _steps, "CriticalStep": _step,
             "RingResult": _ring, "SignoriniResult": _signorini, "BarResult": _bar,
             "Verification": _verification, "WaveRun": _wave_run}


def test_every_result_type_has_an_instance_here():
    assert {t.__name__ for t in _all_result_types()} == set(INSTANCES)


@pytest.fixture(scope="module", params=sorted(INSTANCES))
def result(request):
    return INSTANCES[request.param]()


def test_labels_are_words_from_the_result(result):
    title = result.title()
    assert isinstance(title, str) and "\n" not in title and title.strip()
    lines = result.header_lines()
    assert all(isinstance(x, str) and "\n" not in x for x in lines)
    for text in [title, *lines]:
        assert not REPR.search(text), text
    cols = result.columns()
    assert cols and all(isinstance(c, str) for c in cols)
    assert all(set(row) <= set(cols) for row in result.rows())


def test_every_format_carries_the_failures(result):
    fails = failure_lines(result)
    csv_text = result.to_csv()
    assert csv_text.startswith(f"# {result.title()}\n")
    for f in fails:
        assert f"# failure: {f}" in csv_text
    data = json.loads(result.to_json())
    assert data == json.loads(json.dumps(result.to_dict(), allow_nan=False))
    if type(result).__name__ != "SeriesTable":  # the documented series records (no failures
        assert data["failures"] == fails       # exist: the derivation is exact)
        assert len(data["rows"]) == len(result.rows())
    text = result.to_text()
    if type(result).__name__ not in ("SeriesTable",):
        assert all(f"failure: {f}" in text for f in fails[:10]) or not fails or \
            "not " in text  # Verification's text names the claims that do not hold
    for fmt in FORMATS:
        assert render(result, fmt).endswith("\n")


def test_the_planted_failures_are_there():
    # the instances above that carry failures do carry them (the test can fail both ways)
    for name in ("BranchTable", "ModeTable", "ExactBranches", "Velocities", "RingResult",
                 "Verification", "SlownessTable"):
        assert failure_lines(INSTANCES[name]()), name


def test_short_repr_html_and_dataframe(result):
    r = repr(result)
    assert "\n" not in r and len(r) < 260, r
    html = result._repr_html_()
    assert html.startswith("<") and "<script" not in html
    frame = result.to_dataframe()
    assert len(frame) == len(result.rows()) and list(frame.columns) == list(result.columns())
    assert frame.attrs["title"] == result.title()


def test_undefined_values_are_empty_never_nan(result):
    csv_text = result.to_csv()
    body = [ln for ln in csv_text.splitlines() if not ln.startswith("#")]
    assert not any(re.search(r"(^|,)(nan|inf|-inf)(,|$)", ln) for ln in body)


def test_front_door_and_commands_return_rendered_results():
    # every function a user calls for a result returns one that renders itself
    from dispersion.answers.branch_table import branch_table
    from dispersion.answers.critical_steps import critical_steps
    from dispersion.answers.series_table import series_table

    got = [dispersion.lamb_modes("steel", 1.0, frequency_khz=100),
           dispersion.exact_branches([0.5], 0.3, 2.0),
           dispersion.patch().branches([0.5], 0.3),
           branch_table(exact_only=True, count=2, kappa_max=0.5, omega_max=1.0),
           series_table("S0", 2, exact=True), critical_steps(["lumped"], 1, model="bar")]
    assert all(isinstance(r, Rendered) for r in got)


def test_text_is_rounded_and_aligned_csv_keeps_every_digit():
    t = dispersion.lamb_modes("steel", 3.0, frequency_khz=200)
    text = t.to_text().splitlines()
    head = next(i for i, ln in enumerate(text) if ln.startswith("f [kHz]"))
    table = text[head:head + 5]
    assert len({len(ln) for ln in table[:2]}) == 1  # header and rule line up
    assert "5414.646 " in t.to_text() and "5414.646094137197" in t.to_csv()
