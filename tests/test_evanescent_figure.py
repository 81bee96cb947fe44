"""The evanescent modes' figure (dispersion/plotting/evanescent.py) is drawn from the table:
its title, its points and the searched bound; and what the README reads from it: the
imaginary flexural branch A-e1 ends at A1's cut-off c_T / 2d (Graff 1975, sec. 8.1: the
thickness-shear resonance of the plate), where A1 begins to propagate."""
from __future__ import annotations

import pytest

from dispersion.answers.evanescent_mode_table import evanescent_lamb_modes
from dispersion.continuum.layered.layered_plate import layered_plate
from dispersion.materials.materials import material

STEEL = material("steel")


def _table(frequencies, decay_db=40.0):
    return evanescent_lamb_modes(layered_plate([(STEEL, 1.0)]), frequency_khz=frequencies,
                                 decay_db=decay_db, families=("A",))


def test_the_figure_draws_every_root_of_the_table_once_per_panel_it_belongs_to():
    pytest.importorskip("matplotlib")
    from dispersion.plotting.evanescent import figure_evanescent

    table = _table([300.0, 1200.0], decay_db=100.0)   # A-e2 is complex
    rows = table.rows()
    fig = figure_evanescent(table)
    left, right = fig.axes
    assert fig._suptitle.get_text() == table.title()
    points = [ln for ln in left.lines if ln.get_linestyle() == "None"]
    assert sum(len(ln.get_xdata()) for ln in points) == len(rows)
    assert sorted(x for ln in points for x in ln.get_xdata()) == \
        sorted(r["Im k [1/mm]"] for r in rows)
    complex_rows = [r for r in rows if r["kind"] == "complex"]
    assert complex_rows and sum(len(ln.get_xdata()) for ln in right.lines) == len(complex_rows)
    bound = [ln for ln in left.lines if ln.get_linestyle() == ":"]
    h_mm = 0.5
    assert len(bound) == 1 and bound[0].get_xdata()[0] == table.roots.im_max / h_mm


def test_the_imaginary_flexural_branch_ends_at_the_a1_cut_off():
    cut = STEEL.c_T / (2 * 1e-3) / 1e3          # kHz: c_T / 2d, d = 1 mm
    below, above = _table([cut * (1 - 1e-3)]), _table([cut * (1 + 1e-3)])
    assert below.roots.failures == () and above.roots.failures == ()
    assert [r["kind"] for r in below.rows()].count("imaginary") == 1
    assert [r["kind"] for r in above.rows()].count("imaginary") == 0
