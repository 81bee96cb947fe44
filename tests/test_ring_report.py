"""The ring report names its scheme and its spread (``dispersion/report/ring.py``, issue 18).

Rendered from a small synthetic result (no ring is run here); the figures are made up and
only their routing to the page is checked.
"""
from __future__ import annotations

import pytest

import inspect

from dispersion.contact import study
from dispersion.report import ring


def _sig(mass, scheme, stress, flag=None):
    return {"p": 1, "mass": mass, "scheme": scheme, "dt": 0.002, "t_end": 12.0, "seconds": 0.1,
            "stress_rel_l2": stress, "u0_rel_l2": 0.01, "v0_rel_l2": 0.1,
            "energy_drift_percent": 1.0, "initial_energy_change_percent": 0.0,
            "energy_flag": flag}


def _runs(values):
    return [{"dt": dt, "energy_change_percent": e, "contact_events": n, "converged": True,
             "energy_flag": None} for dt, e, n in values]


DATA = {
    "quick": False, "scenario": {"r_inner": 144.0, "r_outer": 160.0, "dt": 0.05},
    "steps_per_impact": 29.5, "sweep_scale": 0.125, "paper": {"lumped": -9.5, "singular": -0.097},
    "dt_fit": {"rate": None, "points": 3, "monotone": False, "residual": None},
    "pair": {m: {"summary": {"converged": True, "energy_change_percent": e, "contact_events": n}}
             for m, e, n in (("lumped", -10.04, 123), ("singular", -0.031, 15))},
    "spread": {"lumped": {"runs": 4, "energy_min": -10.1, "energy_max": -9.7, "events_min": 110,
                          "events_max": 125, "perturbation": 1e-12},
               "singular": {"runs": 2, "energy_min": -0.031, "energy_max": -0.031,
                            "events_min": 15, "events_max": 15, "perturbation": 1e-12}},
    "dt_spread": {
        "lumped": {"runs": _runs([(0.045, -8.6, 101), (0.05, -10.04, 123), (0.055, -10.25, 131)]),
                   "all_runs": 6, "energy_min": -10.25, "energy_max": -8.6, "events_min": 101,
                   "events_max": 131},
        "singular": {"runs": _runs([(0.045, -0.016, 15), (0.05, -0.031, 15), (0.055, -0.036, 15)]),
                     "all_runs": 4, "energy_min": -0.036, "energy_max": -0.016,
                     "events_min": 15, "events_max": 15}},
    "signorini": [_sig("lumped", "kane", 1.169), _sig("consistent", "kane", 0.779),
                  _sig("singular", "kane", 0.31), _sig("lumped", "central", 1.001),
                  _sig("consistent", "central", 0.709), _sig("singular", "central", 0.31),
                  _sig("lumped", "standard", 9.9, flag="grows")],
}


def test_signorini_figures_are_per_scheme_never_the_best_of():
    text = ring.summary(DATA)
    # issue 18: under "Kane's Newmark" the README quoted the central scheme's 1.001 / 0.709
    kane = next(ln for ln in text.splitlines() if ln.strip().startswith("- kane:"))
    central = next(ln for ln in text.splitlines() if ln.strip().startswith("- central:"))
    assert "lumped 1.169" in kane and "consistent 0.779" in kane and "1.001" not in kane
    assert "lumped 1.001" in central and "consistent 0.709" in central
    standard = next(ln for ln in text.splitlines() if ln.strip().startswith("- standard:"))
    assert "UNSTABLE" in standard


def test_ring_figures_carry_their_dt_and_round_off_spread():
    text = ring.summary(DATA)
    assert "dt = 0.045, 0.05, 0.055 s" in text and "-10.25 .. -8.6 %" in text
    assert "101-131 contact events" in text
    page = "\n".join(ring._robust_text(DATA))
    assert "a loss of at least 8.6 % in every run" in page
    assert "0.045: -8.6 (101)" in page and "0.055: -10.2 (131)" in page


def test_scene_history_has_no_typed_figures():
    # every history entry is a scene (fields of Scenario), no figure: the study measures them
    for label, note, fields in study.SCENE_HISTORY:
        assert isinstance(fields, dict) and set(fields) <= set(inspect.signature(
            study.Scenario).parameters)
    src = inspect.getsource(study)
    assert "-8.8" not in src and "-0.03," not in src


def test_signorini_errors_are_reported_as_their_spread():
    # issue 23: a figure that varies between runs is a spread over the stated perturbations
    from dispersion.contact.signorini import SIGNORINI_SPREAD_RULE

    spread = {"runs": 8, **{k: {"min": v, "max": v} for k, v in (
        ("u0_rel_l2", 0.01), ("v0_rel_l2", 0.1), ("energy_drift_percent", 1.0),
        ("energy_error_percent", -1.0), ("energy_growth_percent", 0.0))},
        "stress_rel_l2": {"min": 1.101, "max": 1.173}}
    data = dict(DATA, signorini=[dict(_sig("lumped", "kane", 1.101), spread=spread),
                                 dict(_sig("singular", "kane", 0.354),
                                      spread=dict(spread, stress_rel_l2={"min": 0.354,
                                                                         "max": 0.354}))])
    kane = next(ln for ln in ring.summary(data).splitlines() if ln.strip().startswith("- kane:"))
    assert "lumped 1.101 .. 1.173" in kane and "singular 0.354" in kane
    assert "range over 8 runs" in ring.summary(data)
    assert [ring._err(r, "stress_rel_l2") for r in data["signorini"]] == ["1.101 .. 1.173",
                                                                          "0.354"]
    assert SIGNORINI_SPREAD_RULE in ring._runs_text(data["signorini"])


def test_scheme_elements_and_step_are_rendered_from_the_rows():
    # issue 22 item 2: "Kane's Newmark" and "20 elements" were typed into the page and the
    # README block; here the stored rows say otherwise (values no code path types), and the
    # text must follow them
    data = {**DATA, "pair": {m: {"summary": {**v["summary"], "scheme": "standard"}}
                             for m, v in DATA["pair"].items()},
            "signorini": [{**r, "n_elements": 37, "dt": 0.0031} for r in DATA["signorini"]]}
    text = ring.summary(data)
    assert text.splitlines()[0].endswith("standard Newmark:") and "Kane" not in text
    assert "(P1, 37 elements, dt 0.0031)" in text and "20 elements" not in text
    assert ring._elements_text(DATA["signorini"]).endswith("not recorded (older record)")
    legacy = {k: v for k, v in data.items() if k != "dt_spread"}
    assert "standard Newmark" in ring.summary(legacy) and "Kane" not in ring.summary(legacy)


def test_signorini_rows_store_their_element_count():
    from dispersion.contact.signorini import signorini_1d

    row = study._signorini((1, "singular", "kane", 0.1, 1))
    default = inspect.signature(signorini_1d).parameters["n_elements"].default
    assert row["n_elements"] == default and row["p"] == 1  # the mesh the study runs


def test_figure4_title_names_the_scheme_the_runs_stored():
    # the title was "<raw name> Newmark" ("kane Newmark"); it is the scheme's name as the pages
    # give it, from the stored summary (a value no default produces: the standard scheme)
    pytest.importorskip("matplotlib")
    import numpy as np

    from dispersion.contact.newmark_scheme import SCHEME_TEXT
    from dispersion.plotting.ring import figure4

    t = np.linspace(0.0, 1.0, 50)
    force = np.where((t > 0.2) & (t < 0.4), 1.0, 0.0)
    sc = {"r_inner": 0.9, "r_outer": 1.0, "theta0_deg": 30, "gap": 0.05, "v0": 1.0, "E": 1e6,
          "nu": 0.3, "rho": 1.0, "n_xi_elements": 4, "n_eta_elements": 2, "dt": 0.02,
          "t_end": 1.0}
    runs = [{"summary": {"scheme": "standard", "mass": m, "energy_change_percent": 1.0},
             "scenario": sc,
             "series": {"t": t.tolist(), "contact_force": force.tolist(),
                        "total": (1 + 0.01 * t).tolist()}} for m in ("lumped", "singular")]
    title = figure4(*runs)._suptitle.get_text().replace("\n", " ")
    assert title.startswith(f"Figure 4: {SCHEME_TEXT['standard']}, ") and "kane" not in title
