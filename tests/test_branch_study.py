"""The branches study: data for Figure 2 and the renderer that reads it from JSON alone."""
from __future__ import annotations

import json
import re

import numpy as np
import pytest

from dispersion.discretization.bar_dispersion import bar_dispersion
from dispersion.studies.branch_study import figure2_data, measure_branches
from dispersion.symbolic.plate import plate_patch
from dispersion.report.branches import render
from dispersion.results import dumps

NU = 0.3
PATCH = {"p": 2, "n": 3, "model": "bloch", "r": "7/3", "mass": "consistent", "contact": "top",
         "gamma_s": "0"}


@pytest.fixture(scope="module")
def small_study() -> dict:
    """A real but small study: Figure 2 data on 12 kappas, the other parts minimal."""
    kappa = np.linspace(0, 3, 12)
    fig2, exact = figure2_data(NU, kappa, 4.0, {
        "consistent": plate_patch(model="bloch", r=0.5),
        "singular": plate_patch(model="bloch", r=0.5, mass="singular", gamma_s=0)})
    bd = bar_dispersion((1, 2), elements_per_wavelength=[4.0, 40.0])
    shape = {"label": "S0", "omega": 1.0, "omega_h": 1.01, "mac": 0.99,
             "exact": [[1.0, 1.0], [0.0, 0.0]], "discrete": [[1.0, 1.0], [0.0, 0.0]]}
    data = {
        "quick": True, "nu": NU, "r_figure2": 0.5, "kappa": fig2["kappa"], "omega_max": 4.0,
        "exact": fig2["exact"], "exact_failures": [], "discrete": fig2["discrete"],
        "mpmath_error": 1e-16, "mpmath_points": 1,
        "zgv": [{"label": "S1", "kappa": 0.84, "omega": 2.73}],
        "orders": [{"patch": PATCH, "mass": "consistent", "branch": "S0", "points": 5,
                    "series_order": 4, "series_leading_coefficient": -0.0125,
                    "window": [0.05, 0.3], "fitted": 4.04, "max_log_residual": 0.01,
                    "series_slope": 4.04, "verdict": "fitted"},
                   {"patch": dict(PATCH, mass="singular"), "mass": "singular", "branch": "A0",
                    "points": 0,
                    "series_order": 2, "series_leading_coefficient": 0.0043,
                    "window": None, "fitted": None, "max_log_residual": None,
                    "series_slope": None, "verdict": "no window: (test)"}],
        "per_wavelength": {"r": 2.0, "elements_per_wavelength": [4.0, 40.0],
                           "curves": [{"p": 2, "n": 3, "mass": "consistent", "branch": "S0",
                                       "error": [1e-3, 1e-7]}]},
        "bar": {"elements_per_wavelength": bd.elements_per_wavelength.tolist(),
                "error": {k: v.tolist() for k, v in bd.error.items()}},
        "shapes": {"kappa": 1.0, "y": [-1.0, 1.0], "modes": [shape]},
        "tracer": {"kappa_count": 12, "omega_max": 4.0, "reference": [0.02, 1e-16],
                   "reference_mpmath_error": 2e-16, "mpmath_points": 1,
                   "rows": [{"step": 0.05, "rtol": 1e-15, "time_s": 0.01, "error": 0.0,
                             "failures": 0}]},
        "discrete_speed": [{"p": 2, "n": 3, "mass": "consistent", "time_s": 0.1,
                            "points_per_s": 1e4, "error": 1e-2}],
        "fd_per_omega_aluminium": 3130 / np.pi * 1e-3,
    }
    return json.loads(dumps(data))  # exactly what the renderer gets from disk


def test_figure2_data_pairs_by_shape_and_keeps_the_zone(small_study):
    data = small_study
    sing = data["discrete"]["singular"]
    # shape pairing: the singular mass's second antisymmetric-like mode is not exact A1
    a1 = [e for e, k in zip(sing["paired_error"]["A1"], data["kappa"]) if 0 < k < 1]
    assert all(e is None for e in a1)
    cons = data["discrete"]["consistent"]
    assert all(e is not None and abs(e) < 1e-2 for e, k in
               zip(cons["paired_error"]["S0"], data["kappa"]) if 0 < k < 1)


def test_figure2_draws_labels_and_signed_errors(small_study):
    from dispersion.plotting.branches import figure2

    fig = figure2(small_study)
    ax, ax_err = fig.axes[:2]
    labels = {t.get_text() for t in ax.texts}
    assert {"S0", "A0", "A1", "S1"} <= labels  # mode labels on the exact branches
    assert ax_err.get_yscale() == "symlog"
    names = ax_err.get_legend_handles_labels()[1]
    assert "consistent S0" in names and "singular A1" not in names


@pytest.mark.slow  # five PNGs: about 4 s on a loaded 2-core machine
def test_render_from_json_alone(tmp_path, small_study):
    md = render(small_study, tmp_path)
    links = re.findall(r"\]\(([^)]+)\)", md)
    pngs = [link for link in links if link.endswith(".png")]
    assert len(pngs) == 5
    for link in pngs:
        assert (tmp_path / link).read_bytes()[:4] == b"\x89PNG"
    assert "same through-thickness shape" in md and "ZGV" not in md.split("###")[0]


@pytest.mark.slow
def test_quick_measure_then_render(tmp_path):
    from dispersion.results import load, save

    save(tmp_path / "branches.json", "branches", measure_branches(quick=True))
    md = render(load(tmp_path / "branches.json")["result"], tmp_path)
    for link in re.findall(r"\]\(([^)]+)\)", md):
        assert (tmp_path / link).is_file()


def test_consistent_mass_errors_are_upper_bounds_per_wavelength():
    # Rayleigh-Ritz (min-max within each mirror block): a conforming discretization with the
    # consistent mass over-estimates every frequency of its block, so S0 and A0 errors >= 0
    from dispersion.studies.branch_study import _per_wavelength

    pw = _per_wavelength(NU, quick=True)
    for c in pw["curves"]:
        err = np.array(c["error"])
        if c["mass"] == "consistent":
            assert np.all(err > -1e-12), (c["p"], c["branch"])
            # and it falls with refinement: more elements per wavelength, smaller error
            assert err[-1] < err[len(err) // 2] < err[0]


def test_tracer_accuracy_reference_is_checked_against_mpmath():
    # issue 14: the reference setting of the speed-accuracy chart is compared with mpmath
    from dispersion.continuum.exact_branches import tracer_accuracy

    acc = tracer_accuracy(NU, np.linspace(0, 4, 30), omega_max=4.0,
                          settings=[(0.2, 1e-6), (0.2, 1e-12)], repeat=1, mpmath_points=5)
    assert acc.reference_mpmath_error < 1e-14
    loose, tight = acc.rows
    assert tight["error"] < 1e-11 < loose["error"] < 1e-5


def test_order_tables_are_headed_by_the_patch_the_result_carries(small_study):
    from dispersion.report.branches import summary

    text = summary(small_study)
    # the fixture's patch has r = 7/3, a value no code path types: the heading must come
    # from the stored fields
    assert text.count("**Bloch r = b/h = 7/3, p = 2, n = 3**") == 1  # one table per geometry
    assert "r = b/h = 1/2" not in text and "r = 2" not in text
    rows = [ln for ln in text.splitlines()
            if ln.startswith("| singular (contact top, gamma_s = 0) | A0")]
    assert len(rows) == 1 and "none: no window" in rows[0] and "| empty |" in rows[0]


def test_figure_titles_and_captions_state_the_stored_patches(small_study):
    # issue 22 item 2: the mode-shape figure typed "p = 2, n = 3", the per-wavelength figure
    # "Bloch" and no contact set, the Figure 2 caption "p = 2, n = 3" and "top surface". Here
    # the stored patches carry values no code path types (p = 3, n = 5, r = 7/3, contact
    # bottom, gamma_s = 1/5): every title and caption must state those and nothing else
    from dispersion.plotting.branches import figure_per_wavelength, figure_shapes
    from dispersion.report.branches import _figure2_patches, _figure2_title, _symmetry_note
    from dispersion.symbolic.patch import Patch

    odd = {"p": 3, "n": 5, "model": "bloch", "r": "7/3", "mass": "singular",
           "contact": "bottom", "gamma_s": "1/5", "weights": None, "nu": None}
    spec = Patch.from_dict(odd)

    title = figure_shapes(dict(small_study["shapes"], patch=odd))._suptitle.get_text()
    assert spec.title() in title and "p = 2" not in title

    pw = dict(small_study["per_wavelength"],
              curves=[dict(c, p=3, n=5, patch=odd) for c in small_study["per_wavelength"]["curves"]])
    fig = figure_per_wavelength(pw, small_study["bar"])
    assert all(ax.get_title().endswith("Bloch patch r = b/h = 7/3") for ax in fig.axes[:2])
    labels = fig.axes[0].get_legend_handles_labels()[1]
    assert "p = 3 (n = 5), singular mass (contact bottom, gamma_s = 1/5)" in labels

    data = dict(small_study, discrete={
        "consistent": dict(small_study["discrete"]["consistent"], patch=dict(odd, mass="consistent")),
        "singular": dict(small_study["discrete"]["singular"], patch=odd)})
    caption = _figure2_patches(data, 0.5) + "." + _symmetry_note(data)
    assert ("patch Bloch r = b/h = 7/3, p = 3, n = 5 with consistent mass, singular mass "
            "(contact bottom, gamma_s = 1/5)") in caption
    assert "bottom surface" in caption and "top" not in caption
    assert "p = 2" not in caption and "paper's Figure 2" not in caption
    title = _figure2_title(data, 0.5)
    assert spec.geometry_title() in title and spec.mass_title() in title and "1/2" not in title
