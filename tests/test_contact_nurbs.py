"""Quarter-ring NURBS patch: exact radii, refinement invariance, Greville contact points."""
from __future__ import annotations

import numpy as np
import pytest

from dispersion.contact.assembly import discretize
from dispersion.splines.nurbs import quarter_ring
from dispersion.errors import InputError


@pytest.mark.parametrize("m_xi,m_eta", [(1, 1), (3, 2), (8, 2)])
def test_outer_boundary_lies_on_the_circle(m_xi, m_eta):
    # exact rational quadratic circle (Piegl & Tiller sec. 7.5): |x| = r_outer to round-off
    ring = quarter_ring(1.8, 2.0, m_xi, m_eta, theta0=0.3, center=(0.0, 0.0))
    xy = ring.boundary_points(np.linspace(0, 1, 101))
    assert np.allclose(np.hypot(*xy.T), 2.0, rtol=0, atol=1e-13)
    ang = np.arctan2(xy[:, 1], xy[:, 0])
    assert np.isclose(ang[0], 0.3) and np.isclose(ang[-1], 0.3 + np.pi / 2)


def test_refinement_leaves_geometry_unchanged():
    coarse = quarter_ring(1.0, 1.5, 1, 1, theta0=1.0, center=(0.5, -2.0))
    fine = quarter_ring(1.0, 1.5, 5, 3, theta0=1.0, center=(0.5, -2.0))
    xi = np.linspace(0, 1, 37)
    assert np.allclose(coarse.boundary_points(xi), fine.boundary_points(xi), atol=1e-13)
    # area (pi/4)(R^2 - r^2): 3x3 Gauss on a rational map is not exact; its error must fall
    # as the mesh is refined (one coarse element: 9e-5 relative, measured)
    exact = np.pi / 4 * (1.5**2 - 1.0**2)
    err = [abs(discretize(r).wdet.sum() - exact) / exact for r in (coarse, fine)]
    assert err[0] < 2e-4 and err[1] < 1e-8


def test_gauss_points_lie_between_the_radii_and_rational_basis_sums_to_one():
    ring = quarter_ring(1.8, 2.0, 4, 2)
    disc = discretize(ring)
    assert np.allclose(disc.R.sum(-1), 1.0)  # partition of unity
    assert np.allclose(disc.dR.sum(-2), 0.0, atol=1e-10)
    x = np.einsum("ega,eak->egk", disc.R, ring.points[disc.conn])
    r = np.hypot(*x.reshape(-1, 2).T)
    assert r.min() > 1.8 and r.max() < 2.0


def test_greville_points_count_and_order():
    ring = quarter_ring(1.0, 2.0, 6, 2)
    g = ring.greville_xi()
    assert len(g) == ring.n_xi == 8  # p + n_elements control points along the arc
    assert g[0] == 0 and g[-1] == 1 and np.all(np.diff(g) > 0)
    assert len(ring.outer_indices()) == ring.n_xi


def test_bad_radii_rejected():
    with pytest.raises(InputError, match="r_outer"):
        quarter_ring(2.0, 1.0)
