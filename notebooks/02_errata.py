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
# # The errata table
#
# Each printed series term of the paper (eqs 14-20) is derived again and compared with the
# printed one. The column "reproduced by" lists the discrete models whose derivation gives
# the printed term (Bloch patch with square elements r = 2, the semi-discrete x-exact model,
# and the Bloch patch with h/b = 2 of the Figure 2 caption). The same table is printed by
# `dispersion series --paper` and written to `reports/coefficients.md` by
# `dispersion reproduce`.

# %%
from IPython.display import Markdown

from dispersion.errata import eq13_note, errata_table, format_table

rows = errata_table()
Markdown(format_table(rows, "markdown"))

# %% [markdown]
# Terms that differ from the printed ones:

# %%
[(f"eq ({r.equation})", f"kappa^{r.power}", str(r.derived)) for r in rows if r.status != "match"]

# %% [markdown]
# Eq (13) as printed has (p^2 - q^2)^2 where the standard Rayleigh-Lamb equation has
# (q^2 - k^2)^2. The leading power balance of each form near the origin
# (branch, standard form, printed form):

# %%
eq13_note()
