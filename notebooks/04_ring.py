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
# # The bouncing ring: lumped vs singular mass (paper sec. 3, Figure 4)
#
# A quarter of an elastic ring, one quadratic NURBS patch, bounces on a rigid frictionless
# plane. Contact is enforced by Lagrange multipliers at the Greville abscissae of the outer
# surface and time is integrated by the contact-modified Newmark scheme of Kane et al.
# (paper eqs 6-12). The paper's figure with the ring's dimensions is missing from our copy:
# the scene below is the *reconstructed* default `Scenario`, whose docstring says why each
# value was chosen.

# %%
from dataclasses import replace

from dispersion.contact.bar import simulate_bar
from dispersion.contact.scenario import Scenario
from dispersion.contact.simulate import simulate_ring
from dispersion.plotting.ring import figure4, plot_bar_force

sc = Scenario()
print(f"r = {sc.r_inner}..{sc.r_outer} m, E = {sc.E:.4g} Pa, nu = {sc.nu}, rho = {sc.rho}")
print(f"v0 / c_T = {sc.v0 / sc.shear_wave_speed:.3f}, dt = {sc.dt} s, t_end = {sc.t_end} s")

# %% [markdown]
# ## First the exact case: a bar hitting a wall
# Contact lasts exactly 2L/c with stress rho c v0. The lumped mass makes the contact stress
# oscillate around the exact plateau; the singular mass (no inertia at the contact point)
# follows it.

# %%
bars = {m: simulate_bar(40, mass=m) for m in ("lumped", "singular")}
for m, res in bars.items():
    print(m, {k: round(float(v), 4) for k, v in res.metrics.items()
              if k in ("duration_error", "force_oscillation", "energy_change_percent")})
plot_bar_force(bars).figure  # noqa: B018 (displayed by the notebook)

# %% [markdown]
# ## The ring, both masses (about 20 s each)

# %%
runs = {m: simulate_ring(sc, m) for m in ("lumped", "singular")}
for m, res in runs.items():
    s = res.summary
    print(f"{m:9s} energy change {s['energy_change_percent']:+.3f} %  "
          f"max penetration {s['max_penetration']:.2e} m  contact events {s['contact_events']}  "
          f"rotation {s['final_rotation_deg']:.0f} deg")

# %%
figure4(runs["lumped"], runs["singular"])

# %% [markdown]
# Paper: lumped mass loses 9.5 % of the energy, singular mass 0.097 %. The numbers printed
# above are this code's measurements on the reconstructed scene; the report section
# (`dispersion.report.ring`) adds the time-step sweep and the standard (unmodified) Newmark.
# A shorter run with the unmodified scheme shows energy jumps at the impacts:

# %%
std = simulate_ring(replace(sc, t_end=10.0), "lumped", "standard")
print(f"standard Newmark, lumped: energy change {std.summary['energy_change_percent']:+.2f} % "
      "after 10 s")
