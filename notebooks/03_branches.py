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
# consistent and the singular mass, with square elements h/b = 2 (Bloch r = b/h = 1/2). One
# import does what `dispersion branches --r 1/2 --figure fig2.png` does: the same function,
# the same bounds, the same result.

# %%
# %matplotlib inline
import dispersion

table = dispersion.branch_table(patch=dispersion.Patch(r="1/2"), count=200, paired=True)
table  # a short repr: what was computed, how many rows, how many failures

# %% [markdown]
# The figure is drawn from the result alone; its title is the result's. The error panel pairs
# each exact branch with the discrete mode of the same through-thickness shape (MAC) and
# shows the error with its sign.

# %%
dispersion.figure(table)

# %% [markdown]
# The inputs, in words, and the rows as a table (a DataFrame with pandas, the `dataframe`
# extra): one row per kappa and branch, exact and discrete, with phase and group velocity.

# %%
print("\n".join(table.header_lines()))
table.to_dataframe().head()

# %% [markdown]
# The same exact branches for an aluminium plate 1 mm thick, in the units of the Dispersion
# Calculator (kHz, MHz mm, m/s), with the zero-group-velocity points and the cut-offs: the A1
# cut-off sits at f d = c_T / 2.

# %%
al = dispersion.branch_table(exact=True, material="aluminium", thickness_mm=1.0,
                             kappa_max=4.0, omega_max=6.0, count=300)
print([line for line in al.header_lines() if line.startswith("ZGV")])
print("A1 cut-off:", round(al.cutoffs_khz()["A1"], 2), "kHz; c_T / 2 =",
      dispersion.material("aluminium").c_T / 2e3, "MHz mm")
dispersion.figure(al)

# %% [markdown]
# The calculator's question, frequency in, velocities out: every propagating mode of a 3 mm
# steel plate at 200 kHz, and the shape of A0 through the thickness.

# %%
modes = dispersion.lamb_modes("steel", 3.0, frequency_khz=200)
print(modes.to_text())
dispersion.figure(dispersion.mode_shapes(modes, "A0"))
