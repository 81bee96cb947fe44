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
# %matplotlib inline
import numpy as np

from dispersion.studies.branch_study import figure2_data
from dispersion.symbolic.plate import plate_patch
from dispersion.plotting.branches import figure2, figure_velocities
from dispersion.waves.rayleigh_lamb import cutoff_frequencies
from dispersion.waves.units import ALUMINIUM, physical_branches
from dispersion.waves.velocities import zgv_points

nu, r = 0.3, 0.5  # Figure 2 caption: h/b = 2

# %% [markdown]
# Cut-off frequencies at kappa = 0 come in closed form (thickness-shear and
# thickness-stretch families):

# %%
for kind in "SA":
    print(kind, [(round(w, 4), fam) for w, fam in cutoff_frequencies(kind, nu, 8.0)])

# %% [markdown]
# Exact and discrete branches; the error panel pairs each exact branch with the discrete
# mode of the same through-thickness shape (MAC), and shows the error with its sign.

# %%
kappa = np.linspace(0, 8, 200)
patches = {m: plate_patch(model="bloch", r=r, mass=m) for m in ("consistent", "singular")}
data, exact = figure2_data(nu, kappa, 8.0, patches)
print("exact branches:", sorted(exact.omega), "| failures reported:", exact.failures)
figure2(data, title=f"nu = {nu}, Bloch model r = {r}")

# %% [markdown]
# A result object shows itself briefly (no whole arrays); as a table it is one DataFrame
# (with pandas, the `dataframe` extra): one row per kappa and branch, with group velocity.

# %%
import dispersion  # noqa: E402

singular = dispersion.patch(r="1/2", mass="singular", gamma_s=0).branches(kappa, nu, group=True)
print(repr(exact))
singular.to_dataframe().head()

# %% [markdown]
# Phase and group velocity, with the zero-group-velocity points of the exact branches.

# %%
zgv = zgv_points(nu, 8.0, 8.0, count=200)
print([(z.label, round(z.kappa, 4), round(z.omega, 4)) for z in zgv])
figure_velocities(data, zgv=[vars(z) for z in zgv])

# %% [markdown]
# The same exact branches for an aluminium plate 1 mm thick, in the units of the
# Dispersion Calculator (kHz, MHz mm, m/s): the A1 cut-off sits at f d = c_T / 2.

# %%
from dispersion.waves.exact_branches import trace_branches  # noqa: E402
from dispersion.waves.velocities import exact_velocities  # noqa: E402

al = trace_branches(ALUMINIUM.nu, [0.0, 1.0], 4.0)
pb = physical_branches(al.kappa, al.omega, exact_velocities(al).group, ALUMINIUM, 1.0)
print("A1 cut-off f d =", round(float(pb.fd["A1"][0]), 4), "MHz mm; c_T / 2 =",
      ALUMINIUM.c_T / 2e3)
