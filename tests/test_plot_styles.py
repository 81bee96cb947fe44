"""Every mass rule has its own style in every plot, derived from the rule registry (issue 28:
`plotting/branches.py` coloured 4 of the 7 rules; a new rule gets a style without a table)."""
from __future__ import annotations

from dispersion.plotting.styles import mass_style
from dispersion.mass_rules.mass_rule import RULE_NAMES, user_rule


def test_every_registered_rule_has_its_own_style():
    styles = [mass_style(r) for r in RULE_NAMES]
    assert len(set(styles)) == len(RULE_NAMES)
    assert len({s.colour for s in styles}) == min(len(RULE_NAMES), 10)


def test_a_user_rule_gets_a_stable_style():
    rule = user_rule("my-rule", lambda space: space.M)
    assert mass_style(rule) == mass_style("my-rule") == mass_style(rule)


def test_the_branch_figure_draws_every_rule_in_its_style():
    from dispersion.api import branch_table, figure
    from dispersion.mass_rules.mass_rule import BLOCH_RULE_NAMES

    table = branch_table(masses=list(BLOCH_RULE_NAMES), count=6, kappa_max=1.0, omega_max=3.0)
    drawn = {(line.get_color(), line.get_marker()) for line in figure(table).axes[0].get_lines()
             if line.get_marker() not in (None, "None", "", " ")}
    assert {tuple(mass_style(rule)) for rule in BLOCH_RULE_NAMES} <= drawn


def test_the_scaling_chart_styles_every_rule():
    from dispersion.plotting.speed import plot_scaling

    points = [{"mass": r, "p": 2, "n": n, "seconds": 0.1 * n, "order": 8}
              for r in RULE_NAMES for n in (3, 4)]
    ax = plot_scaling(points).axes[0]
    colours = {ln.get_label().split(",")[0]: ln.get_color() for ln in ax.get_lines()}
    assert {r: colours[r] for r in RULE_NAMES} == {r: mass_style(r).colour for r in RULE_NAMES}
