"""Power-balance series: paper eqs 14-20 derived, and checked by independent computations."""
import mpmath
import pytest
import sympy

from dispersion.errors import DispersionError, InputError
from dispersion.symbolic.plate import P_MAX, dynamic_stiffness, plate_patch
from dispersion.symbolic.power_balance import (MAX_ORDER, MAX_WORK, discrete_series,
                                               format_coefficient)
from dispersion.continuum.exact_series import exact_series, exact_series_raw

nu = sympy.Symbol("nu")
SING = dict(mass="singular", contact="top", gamma_s=0)
BLOCH2 = dict(model="bloch", r=2)


def same(a, b):
    return sympy.cancel(sympy.together(a - b)) == 0


def test_eq14_exact_s0():
    s = exact_series("S0", 6)
    assert same(s[2], 2 / (1 - nu))                                                  # eq 14
    assert same(s[4], -2 * nu**2 / (3 * (1 - nu) ** 3))                              # eq 14
    assert same(s[6], 2 * nu**2 * (7 * nu**2 + 10 * nu - 6) / (45 * (1 - nu) ** 5))  # eq 14


def test_eq15_exact_a0():
    s = exact_series("A0", 6)
    assert same(s[4], 2 / (3 * (1 - nu)))                            # eq 15
    assert same(s[6], 2 * (7 * nu - 17) / (45 * (1 - nu) ** 2))      # eq 15


def test_exact_a0_leading_term_is_kirchhoff_plate():
    # classical plate: omega^2 = D k^4 / (rho 2h), D = E (2h)^3 / (12 (1 - nu^2)),
    # in units h = c_T = 1: Omega^2 = 2/(3(1 - nu)) kappa^4 (Rose 2004, ch. 8)
    assert same(exact_series("A0", 4)[4], sympy.Rational(2, 3) / (1 - nu))


def test_exact_series_against_mpmath_root():
    # independent: solve the tan-form Rayleigh-Lamb equation (Rose 2004) at kappa = 0.1, 40 digits
    with mpmath.workdps(40):
        _check_exact_series_at_kappa_01()


def _check_exact_series_at_kappa_01():
    k, v = mpmath.mpf("0.1"), mpmath.mpf("0.3")
    g = (1 - 2 * v) / (2 * (1 - v))
    for branch, order in (("S0", 16), ("A0", 16)):
        ser = exact_series(branch, order + 2, nu=sympy.Rational(3, 10))
        nxt = ser.pop(order + 2)
        W0 = sum(mpmath.mpf(sympy.Rational(c).p) / sympy.Rational(c).q * k**p for p, c in ser.items())

        def f(W):
            p, q = mpmath.sqrt(g * W - k**2), mpmath.sqrt(W - k**2)
            a = (q**2 - k**2) ** 2
            if branch == "S0":  # p may be imaginary; the products below are real
                val = a * mpmath.cos(p) * mpmath.sin(q) / q + 4 * k**2 * p * mpmath.sin(p) * mpmath.cos(q)
            else:
                val = a * mpmath.sin(p) / p * mpmath.cos(q) + 4 * k**2 * q * mpmath.cos(p) * mpmath.sin(q)
            return mpmath.re(val)

        W = mpmath.findroot(f, W0)
        # the truncation error is the next term, a_18 kappa^18 (itself from the series)
        assert abs((W - W0) / (float(nxt) * k ** (order + 2)) - 1) < 0.1


def test_eq17_eq18_consistent_mass_bloch_square_elements():
    s, a = discrete_series("S0", 6, **BLOCH2), discrete_series("A0", 6, **BLOCH2)
    assert same(s[2], 2 / (1 - nu)) and same(s[4], -2 * nu**2 / (3 * (1 - nu) ** 3))  # eq 17
    printed6 = -(2 * nu**6 - 18 * nu**5 + nu**4 + 10 * nu**2 - 6 * nu + 1) / (
        45 * (1 - nu) ** 5 * (1 - 2 * nu))
    assert same(s[6], -2 * printed6)  # eq 17 kappa^6: derived = -2 x printed (errata)
    assert same(a[4], 2 / (3 * (1 - nu)))                                  # eq 18
    assert same(a[6], (2 * nu**2 + 8 * nu - 29) / (45 * (1 - nu) ** 2))   # eq 18


def test_eq19_eq20_singular_mass_bloch_square_elements():
    s, a = discrete_series("S0", 4, **BLOCH2, **SING), discrete_series("A0", 6, **BLOCH2, **SING)
    assert same(s[2], 2 / (1 - nu))                                                     # eq 19
    assert same(s[4], +2 * (41 * nu**2 - 10 * nu - 35) / (45 * (1 - nu) ** 3))  # eq 19, sign flipped
    assert same(a[4], 2 / (3 * (1 - nu)))                                   # eq 20
    assert same(a[6], (2 * nu**2 - 16 * nu - 25) / (45 * (1 - nu) ** 2))   # eq 20


def _numeric_omega2(patch, branch, kval, nuval, guess):
    """Root of det K_dyn near ``guess`` at 40 digits (independent of the series engine)."""
    k, W = sympy.symbols("k W")
    Kd = dynamic_stiffness(patch, k, sympy.sqrt(W), sympy.Rational(nuval))
    f = sympy.lambdify((k, W), Kd, "mpmath")
    with mpmath.workdps(40):
        return mpmath.findroot(lambda w: mpmath.det(mpmath.matrix(f(kval, w))), mpmath.mpf(guess))


# the printed terms in dispute, as the paper prints them (dispersion/data/paper_claims.toml)
PRINTED_17_6 = -(2 * nu**6 - 18 * nu**5 + nu**4 + 10 * nu**2 - 6 * nu + 1) / (
    45 * (1 - nu) ** 5 * (1 - 2 * nu))
PRINTED_19_4 = -2 * (41 * nu**2 - 10 * nu - 35) / (45 * (1 - nu) ** 3)


@pytest.mark.parametrize("printed,branch,kw,power", [(PRINTED_17_6, "S0", {}, 6),
                                                     (PRINTED_19_4, "S0", SING, 4)])
def test_disputed_terms_against_high_precision_eigenvalue(printed, branch, kw, power):
    # (W(kappa) - sum_{j < power} a_j kappa^j) / kappa^power -> a_power as kappa -> 0:
    # the derived coefficient fits, the printed one does not
    patch = plate_patch(**BLOCH2, **kw)
    ser = discrete_series(branch, power + 2, **BLOCH2, **kw, nu=sympy.Rational(3, 10))
    printed = printed.subs(nu, sympy.Rational(3, 10))
    guess = sum(float(c) * 0.01**p for p, c in ser.items())
    with mpmath.workdps(40):
        kval = mpmath.mpf("0.01")
        W = _numeric_omega2(patch, branch, kval, "0.3", guess)
        lower = sum(mpmath.mpf(sympy.Rational(c).p) / sympy.Rational(c).q * kval**p
                    for p, c in ser.items() if p < power)
        fitted = (W - lower) / kval**power
    tol = 10 * abs(float(ser[power + 2])) * float(kval) ** 2
    assert abs(fitted - float(ser[power])) < tol
    assert abs(fitted - float(printed)) > 100 * tol


def test_nu_zero_s0_is_the_quadratic_spline_bar():
    # nu = 0 decouples u_x = const: Omega^2 = 2 d/m, the 1D quadratic-spline bar, whose closed
    # form from the stencils above is 20 (1 - c)(2 + c) / (16 + 13 c + c^2), c = cos(kappa r),
    # per element length squared (Cottrell et al. 2006, sec. 3)
    k = sympy.Symbol("kappa")
    c = sympy.cos(2 * k)
    bar = 2 * 20 * (1 - c) * (2 + c) / (4 * (16 + 13 * c + c**2))
    taylor = sympy.series(bar, k, 0, 12).removeO()
    ser = discrete_series("S0", 10, **BLOCH2, nu=0)
    assert all(sympy.simplify(taylor.coeff(k, p) - ser[p]) == 0 for p in ser)
    assert discrete_series("S0", 8, nu=0, model="x-exact") == {2: 2, 4: 0, 6: 0, 8: 0}  # x-exact: Omega^2 = 2 kappa^2


def test_split_and_full_determinant_agree():
    for branch in ("S0", "A0"):
        assert discrete_series(branch, 8, split=True) == discrete_series(branch, 8, split=False)


def test_symbolic_aspect_ratio_specialises_to_numeric():
    for branch in ("S0", "A0"):
        sym = discrete_series(branch, 6, model="bloch")
        num = discrete_series(branch, 6, model="bloch", r=2)
        r = sympy.Symbol("r", positive=True)
        assert all(same(sym[p].subs(r, 2), num[p]) for p in num)


@pytest.mark.parametrize("mass,first_error", [("consistent", 6), ("lumped", 4), ("singular", 4)])
def test_order_of_first_error_term(mass, first_error):
    # paper, end of sec. 2: S0 error starts at kappa^6 for CMM, kappa^4 for the singular mass
    ex = exact_series("S0", 8)
    ds = discrete_series("S0", 8, **BLOCH2, mass=mass)
    diff = [p for p in ds if not same(ds[p], ex[p])]
    assert min(diff) == first_error


def test_higher_degree_and_more_control_points_converge_to_exact_leading_terms():
    ex = exact_series("A0", 6)
    for p, n in [(2, 4), (3, 4), (3, 5)]:
        a = discrete_series("A0", 6, p=p, n=n, model="x-exact")
        assert same(a[4], ex[4])


def test_printed_eq13_has_no_a0_branch():
    with pytest.raises(DispersionError, match="no unique simple non-zero root"):
        exact_series("A0", 6, form="printed")


def test_bad_input():
    with pytest.raises(InputError, match="order"):
        discrete_series("A0", 2)
    with pytest.raises(InputError, match="branch"):
        exact_series("S1", 4)
    with pytest.raises(InputError, match="nu must lie"):
        exact_series("S0", 4, nu=-2)


def test_bounds_refuse_up_front_naming_parameter_and_bound():
    with pytest.raises(InputError, match=f"order must be <= {MAX_ORDER['exact']}"):
        exact_series("S0", 100_000)
    with pytest.raises(InputError, match=f"order must be <= {MAX_ORDER['discrete']}"):
        discrete_series("S0", 400)
    with pytest.raises(InputError, match=f"<= {MAX_WORK}"):
        discrete_series("S0", 8, p=20, n=21)
    with pytest.raises(InputError, match=rf"degree p must be an integer in \[1, {P_MAX}\]"):
        discrete_series("S0", 8, p=100, n=101)  # the degree is named first


@pytest.mark.parametrize("kw", [
    dict(mass="singular", contact="top", gamma_s=sympy.Rational(1, 2)),
    # about 2 s each: the slow run; the paper's singular mass above stays in the default run
    pytest.param(dict(mass="singular-lumped", contact="top", gamma_s=0), marks=pytest.mark.slow),
    pytest.param(dict(mass="singular", contact="bottom", gamma_s=sympy.Rational(1, 3)),
                 marks=pytest.mark.slow),
])
def test_one_sided_masses_against_high_precision_eigenvalue(kw):
    # any mass without the mirror symmetry goes through the full determinant: the series must
    # predict the 40-digit root of det K_dyn at kappa = 0.01 to within its next term
    patch = plate_patch(p=2, n=5, **BLOCH2, **kw)
    for branch in ("S0", "A0"):
        ser = discrete_series(branch, 8, p=2, n=5, **BLOCH2, **kw, nu=sympy.Rational(3, 10))
        nxt = ser.pop(8)
        guess = sum(float(c) * 0.01**p for p, c in ser.items())
        with mpmath.workdps(40):
            k = mpmath.mpf("0.01")
            W = _numeric_omega2(patch, branch, k, "0.3", guess)
            W0 = sum(mpmath.mpf(sympy.Rational(c).p) / sympy.Rational(c).q * k**p
                     for p, c in ser.items())
            assert abs((W - W0) / (float(nxt) * k**8) - 1) < 0.05


def test_mirror_split_is_only_a_speed_up_for_every_symmetric_mass():
    for mass in ("lumped", "singular"):
        kw = dict(p=2, n=4, **BLOCH2, mass=mass, contact="both")
        for branch in ("S0", "A0"):
            assert discrete_series(branch, 6, split=True, **kw) == \
                discrete_series(branch, 6, split=False, **kw)


def test_printed_coefficients_parse_back_to_the_sympy_output():
    # the CLI's flint-only strings are the same rational functions as the API's sympy values
    for k, num, den in exact_series_raw("S0", 10):
        text = format_coefficient(num, den)
        assert same(sympy.sympify(text, locals={"nu": nu}), exact_series("S0", 10)[k])
