"""Series of the exact Rayleigh-Lamb branches S0 and A0 through the origin (paper eqs 14-15).

The characteristic function is :func:`dispersion.continuum.rayleigh_lamb.frequency_function`
itself, evaluated on truncated power series over QQ[g] with g = (c_T/c_L)^2, and solved
order by order by the generic engine :func:`dispersion.symbolic.power_balance.solve_branch`.

>>> exact_series("S0", 4)[2]
-2/(nu - 1)
"""
from __future__ import annotations

import flint

from dispersion.symbolic import series_kernel as _k
from dispersion.symbolic.series_kernel import _from_uni
from dispersion.symbolic.power_balance import (BRANCHES, _to_expr, check_request,
                                               solve_branch)
from dispersion.continuum.rayleigh_lamb import frequency_function

__all__ = ["exact_leading_balance", "exact_series", "exact_series_raw"]


def _exact_build(kind: str, sigma: int, form: str):
    # Over QQ[w, g], g = (c_T/c_L)^2 = (1 - 2 nu)/(2 (1 - nu)): polynomial arithmetic only.
    ctx = _k.context(("g",))
    w, g = ctx.gens()

    def build(D):
        t = _k.Series.gen_t(ctx, D)
        W = _k.Series(ctx, [0] * sigma + [w], D)
        return frequency_function(kind, t, W, None, lambda z: _k.entire(z, "C"),
                                  lambda z: _k.entire(z, "S"), form, ratio=g)

    return ctx, build


def _g_to_nu(p, e: int):
    """p(g) (2 (1 - nu))^e with g = (1 - 2 nu) / (2 (1 - nu)), as an ``fmpq_poly`` in nu.

    With Y = 2 - 2 nu, 1 - 2 nu = Y - 1 and g = 1 - 1/Y, so p(g) Y^e = Y^e P(1/Y) with
    P(v) = p(1 - v): two polynomial compositions and a reversal, all in FLINT.
    """
    terms = {int(mon[1]): c for mon, c in p.to_dict().items()}
    if not terms:
        return flint.fmpq_poly(0)
    coeffs = [flint.fmpq(0)] * (max(terms) + 1)
    for i, c in terms.items():
        coeffs[i] = c
    P = flint.fmpq_poly(coeffs)(flint.fmpq_poly([1, -1])).coeffs()  # P(v) = p(1 - v)
    R = [flint.fmpq(0)] * (e + 1)
    for i, c in enumerate(P):  # Y^e P(1/Y) = sum_i P_i Y^(e - i)
        R[e - i] = c
    return flint.fmpq_poly(R)(flint.fmpq_poly([2, -2]))


def exact_series_raw(branch: str, order: int, form: str = "standard") -> list[tuple]:
    """``[(power of kappa, num, den)]`` as flint polynomials in nu (context ``(w, nu)``).

    The sympy-free core of :func:`exact_series` (the CLI prints these directly).
    """
    kind, sigma, order = check_request(branch, order, exact=True)
    ctx, build = _exact_build(kind, sigma, form)
    nums, dens = solve_branch(build, sigma, order, 2 * sigma)  # the lowest power is t^(2 sigma)
    ctx_nu = _k.context(("nu",))
    out = []
    for k, (a, b) in enumerate(zip(nums, dens)):
        e = max(a.degrees()[1], b.degrees()[1])
        num, den = _g_to_nu(a, e), _g_to_nu(b, e)
        g = num.gcd(den)  # monic, as fmpq_mpoly's gcd: the same reduced pair
        out.append((2 * (sigma + k), _from_uni(ctx_nu, num / g), _from_uni(ctx_nu, den / g)))
    return out


def exact_series(branch: str, order: int, nu=None, form: str = "standard",
                 factor: bool = True) -> dict:
    """Series of the exact Rayleigh-Lamb branch S0 or A0 (paper eqs 14-15) to kappa^order.

    The characteristic function is :func:`dispersion.continuum.rayleigh_lamb.frequency_function` itself,
    evaluated on truncated power series over QQ[g]. ``form="printed"`` uses eq (13) as
    printed; it has no such branch and raises :class:`DispersionError`. ``nu``: a number
    substituted at the end (None: symbolic), or an isotropic
    :class:`~dispersion.materials.elastic_law.ElasticLaw` (other laws have no closed form).

    >>> exact_series("A0", 6, nu=0)
    {4: 2/3, 6: -34/45}
    """
    import sympy

    from dispersion.materials.elastic_law import as_law

    law = as_law(nu)
    if law.kind != "isotropic":
        law.poisson_ratio("exact Rayleigh-Lamb series")  # refused, in words
    series = {k: _to_expr(a, b, (sympy.Symbol("nu"),), factor)
              for k, a, b in exact_series_raw(branch, order, form)}
    return law.substitute(series)


def exact_leading_balance(branch: str, form: str = "standard"):
    """Leading balance q0(w) of the Rayleigh-Lamb equation for Omega^2 = w kappa^(2 sigma).

    Its non-zero roots are the admissible leading coefficients; used by the errata to show
    that the printed eq (13) has no A0 branch and a wrong S0 speed.

    >>> exact_leading_balance("S0")
    w*(nu*w - w + 2)/(nu - 1)
    """
    kind, sigma, _ = check_request(branch, 2 * BRANCHES[branch][1], exact=True)
    _, build = _exact_build(kind, sigma, form)
    D = 4
    F = build(D)
    while F.valuation() is None or F.valuation() > D:
        D *= 2
        F = build(D)
    import sympy

    q0 = F.coeffs[F.valuation()]
    w, g, nu = sympy.symbols("w g nu")
    expr = 0
    for mon, c in q0.to_dict().items():
        expr += sympy.Rational(int(c.p), int(c.q)) * w ** mon[0] * g ** mon[1]
    return sympy.factor(expr.subs(g, (1 - 2 * nu) / (2 * (1 - nu))))
