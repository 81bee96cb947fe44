"""Zero-group-velocity points of layered plates (dispersion/continuum/layered/layered_zgv.py)."""
from __future__ import annotations

import pytest

from dispersion.continuum.layered.layered_plate import layered_plate
from dispersion.continuum.layered.layered_zgv import zgv_points
from dispersion.continuum.frequency import zgv_points_below
from dispersion.materials.materials import material


@pytest.mark.slow
@pytest.mark.parametrize("name", ["steel", "aluminium", "pmma"])
def test_one_layer_has_the_rayleigh_lamb_zgv_points(name):
    # the isotropic code's ZGV points (its own certified route) up to Omega 5
    m = material(name)
    ours = zgv_points(layered_plate([(m, 1.0)]), 5.0)
    ref = [(p.label, p.kappa, p.omega) for p in zgv_points_below(m.nu, 5.0)]
    assert [p[0] for p in ours] == [p[0] for p in ref]
    for (_, k, w), (_, k_ref, w_ref) in zip(ours, ref):
        assert abs(w / w_ref - 1) < 1e-12 and abs(k / k_ref - 1) < 1e-8
