"""The mass rules of the recent lumping literature, as entries of the one registry.

Each entry is registered by :mod:`dispersion.mass_rules.mass_rule` under its name; every rule
is written in its *Galerkin* form (a symmetric mass for the B-spline stiffness), and where the
paper's scheme is Petrov-Galerkin the equivalence is exact (stated per rule, tested):

==========================  ==================================================================
``dual-lumped``             approximate-dual test functions, row-sum lumped (Nguyen et al.
                            2023): Petrov-Galerkin :math:`S K u = \\omega^2 u`, i.e. the
                            Galerkin mass :math:`S^{-1}` (Hiemstra et al. 2025); along x the
                            stiffness symbol is multiplied by :math:`s(\\theta)` and the mass is 1
``dual-gram``               dual basis of the inverted Gram matrix (Held et al. 2023, "IG"):
                            :math:`G^{-1} K u = \\omega^2 u`, the consistent spectrum; diagonal
                            Petrov-Galerkin mass, *dense* stiffness
``dual-consistent``         approximate dual without lumping (Held et al. 2023, "AD"):
                            :math:`S K u = \\omega^2 S G u`, the consistent spectrum; banded
                            non-symmetric mass to solve every step, wider stiffness
``interpolatory-nodal``     interpolatory spline basis at the Greville points with nodal
                            quadrature (Voet, Sande 2025): :mod:`interpolatory_spline`
``sms``                     selective mass scaling of the lumped mass, beta = 1/2
                            (Olovsson et al. 2005; Tkachuk, Bischoff 2013): :mod:`mass_scaling`
``sem-consistent``,         the classical comparator: C0 Lagrange elements of degree p,
``sem-lumped``              consistent or Gauss-Lobatto-Legendre lumped (spectral elements);
                            they change the *basis* (``basis = "lagrange"``): :mod:`lagrange_sem`
==========================  ==================================================================

Non-symmetric pencils never reach the solvers: a Petrov-Galerkin pencil
:math:`(S K, S M)` or :math:`(S K, I)` is the Galerkin pencil :math:`(K, M)` or
:math:`(K, S^{-1})` multiplied from the left by the invertible S, which changes no eigenvalue;
a user rule that is not symmetric is refused by :func:`dispersion.mass_rules.mass_check.check_mass`
with the reason.

>>> sorted(ENTRIES)
['dual-consistent', 'dual-gram', 'dual-lumped', 'interpolatory-nodal', 'sem-consistent', 'sem-lumped', 'sms']

References
----------
T.-H. Nguyen, R. R. Hiemstra, S. Eisentraeger, D. Schillinger, CMAME 417 (2023) 116233,
doi:10.1016/j.cma.2023.116233, arXiv:2305.12916. R. R. Hiemstra, T.-H. Nguyen,
S. Eisentraeger, W. Dornisch, D. Schillinger, Comput. Mech. 76 (2025) 205-226,
doi:10.1007/s00466-025-02596-3. S. Held, S. Eisentraeger, W. Dornisch, "An efficient mass
lumping scheme for isogeometric analysis based on approximate dual basis functions",
Technische Mechanik (2024), arXiv:2306.12257. Y. Voet, E. Sande, arXiv:2510.13510 (2025).
L. Olovsson, K. Simonsson, M. Unosson, IJNME 63 (2005) 1436-1445, doi:10.1002/nme.1293.
A. Tkachuk, M. Bischoff, Comput. Mech. 52 (2013) 563-570, doi:10.1007/s00466-012-0808-4.
"""
from __future__ import annotations

from dispersion.mass_rules.explicit_cost import ExplicitCost
from dispersion.mass_rules.mass_check import MassProperties

__all__ = ["ENTRIES", "approximate_dual_entry", "sms_entry"]


def _kv(space, name):
    if space.kv is None:
        raise _no_kv(name)
    return space.kv


def _no_kv(name):
    from dispersion.errors import InputError

    return InputError(f"mass rule {name!r} evaluates the basis and needs a 1D B-spline space "
                      "(knot vector); this space has none")


def _like(A, space):
    # the registry converts an exact matrix to the kind of a float space
    # (dispersion.mass_rules.mass_rule, where the entries are registered)
    return A


def approximate_dual_entry(q: int | None = None) -> dict:
    """The registry entry of approximate-dual lumping with reproduction degree ``q``
    (None: the degree p, full reproduction)."""
    from dispersion.errors import InputError

    if q is not None and (isinstance(q, bool) or not isinstance(q, int) or q < 0):
        raise InputError(f"reproduction degree q must be a non-negative integer, got {q!r}")

    def build(space):
        from dispersion.mass_rules.approximate_dual import customized_mass

        kv = _kv(space, "dual-lumped")
        if q is not None and q > kv.p:
            raise InputError(f"reproduction degree q must lie in [0, p = {kv.p}], got {q}")
        return _like(customized_mass(kv, q), space)

    def x_stiffness(p):
        from dispersion.mass_rules.approximate_dual import dual_symbol

        return dual_symbol(p, None if q is None else min(q, p))

    return dict(build=build, states=MassProperties(),
                periodic=lambda p: {0: 1}, x_stiffness=x_stiffness,
                cost=ExplicitCost("sparse", "banded",
                                  "Petrov-Galerkin: diagonal lumped mass I and stiffness S K; "
                                  "Galerkin form: M^-1 = S applied as a banded product"),
                description="approximate-dual Petrov-Galerkin, row-sum lumped "
                            f"(reproduction degree {'p' if q is None else q}; Galerkin mass "
                            "S^-1)")


def sms_entry(beta=None) -> dict:
    """The registry entry of selective mass scaling with parameter ``beta``."""
    from dispersion.mass_rules.mass_scaling import SMS_BETA, check_beta

    beta = SMS_BETA if beta is None else check_beta(beta)

    def build(space):
        from dispersion.mass_rules.mass_scaling import scaled_mass

        return _like(scaled_mass(_kv(space, "sms"), beta), space)

    def periodic(p):
        from dispersion.mass_rules.mass_scaling import scaled_row

        return scaled_row(p, beta)

    return dict(build=build, states=MassProperties(), periodic=periodic,
                cost=ExplicitCost("sparse", "solve",
                                  "non-diagonal scaled mass: an iterative or banded solve"),
                description=f"selective mass scaling M_L + beta h^2 int N'N'^T, beta = {beta}")


def _consistent(space):
    return space.M


def _interpolatory(space):
    from dispersion.splines.interpolatory_spline import interpolatory_mass

    return _like(interpolatory_mass(_kv(space, "interpolatory-nodal")), space)


def _greville_row(p):
    # uniform periodic knots: every interpolatory weight is the element length (translation
    # invariance and exactness on constants), so the row is nodal-greville's; the middle row
    # of a finite mesh is not (the cardinal splines reach its boundary)
    from dispersion.splines.spline_mass import PERIODIC_ROWS

    return PERIODIC_ROWS["nodal-greville"](p)


def _sem_consistent(space):
    return space.M  # the plate hands the C0 space's own Gram matrix (basis "lagrange")


def _sem_lumped(space):
    from dispersion.splines.spline_mass import lobatto_matrix

    return _like(lobatto_matrix(_kv(space, "sem-lumped")), space)


#: name -> registry entry (build, states, x rule, periodic row, x stiffness factor, cost).
ENTRIES = {
    "dual-lumped": dict(approximate_dual_entry(), x_rule="dual-lumped"),
    "dual-gram": dict(build=_consistent, states=MassProperties(), x_rule="consistent",
                      cost=ExplicitCost("dense", "diagonal",
                                        "test functions G^-1 N: Petrov-Galerkin mass I, "
                                        "stiffness G^-1 K fully populated"),
                      description="dual basis of the inverted Gram matrix (Petrov-Galerkin; "
                                  "consistent spectrum, dense stiffness)"),
    "dual-consistent": dict(build=_consistent, states=MassProperties(), x_rule="consistent",
                            cost=ExplicitCost("banded-wide", "solve",
                                              "test functions S N: banded non-symmetric mass "
                                              "S G solved every step, stiffness S K"),
                            description="approximate-dual Petrov-Galerkin without lumping "
                                        "(consistent spectrum)"),
    "interpolatory-nodal": dict(build=_interpolatory, states=MassProperties(),
                                x_rule="nodal-greville", periodic=_greville_row,
                                cost=ExplicitCost("sparse", "solve",
                                                  "in the interpolatory basis: diagonal mass, "
                                                  "dense stiffness; in B-spline coordinates: "
                                                  "collocation solves"),
                                description="interpolatory spline basis at the Greville "
                                            "points, nodal quadrature"),
    "sms": dict(sms_entry(), x_rule="sms"),
    "sem-consistent": dict(build=_sem_consistent, states=MassProperties(), x_rule="consistent",
                           basis="lagrange",
                           cost=ExplicitCost("sparse", "solve", "C0 Lagrange elements"),
                           description="C0 Lagrange elements, consistent mass"),
    "sem-lumped": dict(build=_sem_lumped, states=MassProperties(), x_rule="consistent",
                       basis="lagrange",
                       cost=ExplicitCost("sparse", "diagonal",
                                         "spectral elements: diagonal in the nodal GLL basis"),
                       description="C0 Lagrange elements, Gauss-Lobatto-Legendre lumped "
                                   "(spectral elements)"),
}

