"""Problems as data: a user NURBS patch against a plane, Dirichlet sides, plane stress/strain."""
from __future__ import annotations

import numpy as np
import pytest

from dispersion.contact.material import StVenantKirchhoff
from dispersion.contact.newmark import critical_step, integrate
from dispersion.contact.newmark_scheme import Newmark
from dispersion.contact.problem import Plane, patch_problem, rectangle_patch
from dispersion.errors import InputError

MAT = StVenantKirchhoff(1.0, 0.3)


def _block(mass="singular", plane="stress", **kw):
    patch = rectangle_patch(1.0, 0.5, 4, 2, origin=(0.0, 0.05))
    return patch_problem(patch, StVenantKirchhoff(1.0, 0.3, plane), 1.0, mass, "eta0",
                         Plane((0.0, 0.0), (0.0, 1.0)), **kw)


def test_gap_at_the_greville_points_is_the_distance_to_the_plane():
    model = _block()
    assert np.allclose(model.problem.g0, 0.05)  # bottom side at y = 0.05 above y = 0
    tilted = patch_problem(rectangle_patch(1.0, 0.5, 4, 2), MAT, 1.0, "lumped", "eta0",
                           Plane((0.0, -1.0), (1.0, 1.0)))
    # Greville points of p = 2 on 4 elements (x on the bottom side, y = 0); the plane
    # x + y = -1 lies at distance (x + 1) / sqrt(2)
    x = np.array([0.0, 0.125, 0.375, 0.625, 0.875, 1.0])
    assert np.allclose(tilted.problem.g0, (x + 1.0) / np.sqrt(2))


def test_dirichlet_sides_remove_their_dofs():
    free = _block(dirichlet=[("eta1", 0), ("eta1", 1)])
    full = _block()
    n_top = full.patch.n_xi
    assert full.problem.n - free.problem.n == 2 * n_top
    with pytest.raises(InputError, match="dirichlet"):
        _block(dirichlet=[("eta0", 1)])


def test_falling_block_touches_the_plane_and_conserves_momentum_along_it():
    model = _block("singular")
    prob = model.problem
    v0 = np.zeros(prob.n)
    v0[1::2] = -0.2
    v0[0::2] = 0.1  # sliding: a frictionless plane keeps the horizontal momentum
    hist = integrate(prob, np.zeros(prob.n), v0, 0.02, 60)
    mom = np.asarray(hist.momentum)
    assert max(hist.contact_force) > 0
    assert np.ptp(mom[:, 0]) < 1e-10 * abs(mom[0, 0])
    assert min(hist.gap_min) > -1e-10


def test_plane_strain_is_stiffer_than_plane_stress():
    stress = critical_step(_block("lumped", "stress").problem)
    strain = critical_step(_block("lumped", "strain").problem)
    assert strain < stress


def test_singular_mass_has_massless_contact_side():
    prob = _block("singular").problem
    rows = np.asarray(abs(prob.M).sum(axis=1)).ravel()
    n_xi = 6
    assert np.count_nonzero(rows == 0) == 2 * n_xi  # both components of the bottom row
    assert np.isclose(prob.M.sum(), 2 * 0.5)  # translational mass (x and y) kept


@pytest.mark.parametrize("kwargs, name", [
    ({"mass": "heavy"}, "mass"),
    ({"contact_side": "top"}, "contact_side"),
    ({"rho": float("nan")}, "rho"),
])
def test_bad_problem_names_the_parameter(kwargs, name):
    args = dict(patch=rectangle_patch(1.0, 1.0), material=MAT, rho=1.0)
    args.update(kwargs)
    with pytest.raises(InputError, match=name):
        patch_problem(**args)


def test_explicit_scheme_on_a_patch_is_refused_above_its_limit():
    prob = _block("lumped").problem
    dt = critical_step(prob)
    with pytest.raises(InputError, match="stability limit"):
        integrate(prob, np.zeros(prob.n), np.zeros(prob.n), 1.1 * dt, 2, Newmark(beta=0.0))
