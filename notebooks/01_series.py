# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Deriving a dispersion series with `dispersion`
#
# The paper (Tkachuk, Matzen, Kolman, Bischoff, section 2) gives the long-wave series of the
# S0 and A0 branches of a plate, exact (eqs 14-15) and for a quadratic B-spline patch with
# three control points through the thickness (eqs 17-20). Here we derive them with the
# package: `exact_series` expands the Rayleigh-Lamb equation, `discrete_series` the
# determinant of the patch's dynamic stiffness (eq 16), both by the method of power balance,
# exactly, as rational functions of Poisson's ratio `nu`.

# %%
import numpy as np
import sympy
from scipy.linalg import eigh

from dispersion.symbolic.plate import numeric_pencil, plate_patch
from dispersion.symbolic.power_balance import NU, discrete_series
from dispersion.continuum.exact_series import exact_series

exact = exact_series("S0", 6)
exact

# %% [markdown]
# The same coefficients as eq 14, transcribed from the paper, for comparison:

# %%
nu = NU
eq14 = {2: 2 / (1 - nu), 4: -2 * nu**2 / (3 * (1 - nu) ** 3),
        6: 2 * nu**2 * (7 * nu**2 + 10 * nu - 6) / (45 * (1 - nu) ** 5)}
{k: sympy.simplify(exact[k] - eq14[k]) for k in eq14}

# %% [markdown]
# ## The discrete patch
#
# Consistent mass (CMM), Bloch model with square elements (aspect ratio r = b/h = 2):

# %%
cmm = discrete_series("S0", 6, model="bloch", r=2, mass="consistent")
{k: sympy.factor(cmm[k] - exact[k]) for k in cmm}

# %% [markdown]
# The first nonzero difference is the error term: kappa^6 for CMM. The singular mass
# (contact on the top surface, paper eqs 2-4) errs already at kappa^4:

# %%
sing = discrete_series("S0", 6, model="bloch", r=2, mass="singular", contact="top", gamma_s=0)
{k: sympy.factor(sing[k] - exact[k]) for k in sing}

# %% [markdown]
# ## One quantity computed two ways
#
# At small kappa the series must match the patch's own eigenvalue; the gap shrinks like the
# first neglected power.

# %%
patch = plate_patch(2, 3, "bloch", 2, mass="consistent")
coeffs = {k: float(v.subs(NU, sympy.Rational(3, 10))) for k, v in cmm.items()}
for kappa in (0.2, 0.1, 0.05):
    K, M = numeric_pencil(patch, 0.3, [kappa])
    Omega2 = eigh(K[0], M[0], eigvals_only=True)
    s0 = Omega2[np.argmin(abs(Omega2 - coeffs[2] * kappa**2))]
    series = sum(c * kappa**k for k, c in coeffs.items())
    print(f"kappa={kappa:5}: eigenvalue {s0:.12f}  series {series:.12f}  "
          f"rel. gap {abs(series / s0 - 1):.2e}")

# %% [markdown]
# ## Any mass, any size
#
# The one-sided singular mass breaks the mirror symmetry y -> -y, so the engine works on the
# full determinant. It eliminates fraction-free over truncated power series (flint), so the
# cost grows polynomially with the number of control points n, not exponentially. With five
# control points the series still starts with the exact plate speed, and errs at kappa^4:

# %%
sing5 = discrete_series("S0", 6, p=2, n=5, model="bloch", r=2, mass="singular", contact="top",
                        gamma_s=sympy.Rational(1, 2))
{k: sympy.factor(sing5[k] - exact[k]) for k in sing5}
