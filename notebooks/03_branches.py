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
# # Dispersion branches: exact Rayleigh-Lamb and the B-spline plate patch
#
# The paper's Figure 2 (right) compares the exact branches of a plate of thickness 2h with
# those of a quadratic B-spline patch (three control points through the thickness), for the
# consistent and the singular mass. Here: the exact branches traced from the entire-function
# frequency equation, all discrete branches from one batched eigenvalue solve, their error
# against the exact partner, and the order of accuracy fitted from it.

# %%
import numpy as np

from dispersion.branches import discrete_branches, fitted_order, predicted_error, relative_error
from dispersion.plate import plate_patch
from dispersion.plotting.branches import figure2
from dispersion.rayleigh_lamb import cutoff_frequencies, trace_branches

nu, r = 0.3, 0.5  # Figure 2 caption: h/b = 2

# %% [markdown]
# Cut-off frequencies at kappa = 0 come in closed form (thickness-shear and
# thickness-stretch families):

# %%
for kind in "SA":
    print(kind, [(round(w, 4), fam) for w, fam in cutoff_frequencies(kind, nu, 8.0)])

# %%
kappa = np.linspace(0, 8, 400)
exact = trace_branches(nu, kappa, 8.0)
print("exact branches:", sorted(exact.omega), "| failures reported:", exact.failures)
results = []
for mass in ("consistent", "singular"):
    d = discrete_branches(plate_patch(model="bloch", r=r, mass=mass), nu, kappa)
    results.append((mass, d, relative_error(d, exact)))
fig = figure2(exact, results, title=f"nu = {nu}, Bloch model r = {r}")
fig  # noqa: B018

# %% [markdown]
# Order of accuracy: the fitted slope of the relative error of Omega at small kappa against
# the leading error term of the series (`discrete_series - exact_series`).

# %%
small = np.geomspace(0.04, 0.16, 5)
ex = trace_branches(nu, small, 4.0)
for mass in ("consistent", "singular"):
    err = relative_error(discrete_branches(plate_patch(mass=mass), nu, small), ex)
    for b in ("S0", "A0"):
        q, c = predicted_error(b, nu, mass=mass)
        print(f"{mass:10s} {b}: fitted {fitted_order(small, err[b]):.2f}, series {q}")
