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
# # Verifying a manuscript's equations
#
# A claims file states what a manuscript prints about a branch: its series (per power of
# kappa or as the whole expression, in sympy text or LaTeX), the order of its error, or its
# value at one wavenumber. `dispersion verify FILE` derives each claim again and compares
# exactly; the same check runs in Python (`dispersion.claims`) and in pytest
# (`dispersion.testing`). The format is described in the docstring of `dispersion.claims`.
#
# Here a small file holds two printed equations of the paper: eq (15) (the exact A0 branch)
# and eq (18) (A0 of the quadratic patch with consistent mass, Bloch model, r = 2), the
# second with a typo in its kappa^6 coefficient (-28 instead of -29).

# %%
import tempfile
from pathlib import Path

from IPython.display import Markdown

from dispersion.claims import format_results, junit_xml, verify_file
from dispersion.testing import assert_series

claims = """
[[claim]]
name = "eq 15"
source = "paper eq (15)"
model = "rayleigh-lamb"
branch = "A0"
series = "2/(3*(1-nu))*kappa^4 + 2*(7*nu - 17)/(45*(1-nu)^2)*kappa^6 + O(kappa^8)"

[[claim]]
name = "eq 18"
source = "paper eq (18)"
model = "bloch"
r = 2
mass = "consistent"
branch = "A0"
coefficients = {4 = "2/(3*(1-nu))", 6 = "(2*nu^2 + 8*nu - TYPO)/(45*(1-nu)^2)"}
"""
scratch = tempfile.TemporaryDirectory(prefix="manuscript-")  # not the folder we run in
path = Path(scratch.name) / "manuscript.toml"
path.write_text(claims.replace("TYPO", "28"))
result = verify_file(path, jobs=1)
Markdown(format_results(result.results, "markdown"))

# %% [markdown]
# The typo is named, with the simplest description of the difference. `result.passed` is
# what `dispersion verify` turns into its exit status (1 here):

# %%
result.passed, [(r.name, r.difference) for r in result.results if not r.passed]

# %% [markdown]
# With the coefficient as printed in the paper (-29), every claim holds (exit status 0),
# and the JUnit XML report (`dispersion verify --junit FILE`) shows each claim as a test case:

# %%
path.write_text(claims.replace("TYPO", "29"))
result = verify_file(path, jobs=1)
print(result.passed)
print(junit_xml(result)[:600])

# %% [markdown]
# In a test suite, `dispersion.testing.assert_claims_file(path)` (or `assert_series` for an
# inline claim) raises an `AssertionError` that shows printed and derived term by term:

# %%
try:
    assert_series("A0", {4: "2/(3*(1-nu))", 6: "(2*nu^2 + 8*nu - 28)/(45*(1-nu)^2)"},
                  name="eq 18 (typo)", model="bloch", r=2, mass="consistent")
except AssertionError as exc:
    print(exc)

# %%
scratch.cleanup()  # the manuscript file was ours: nothing is left behind
