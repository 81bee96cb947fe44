"""Errata table (paper eqs 13-20): status of each printed term against the derivation."""
from dispersion.errata import eq13_note, errata_table, format_table


def test_errata_statuses():
    rows = {(r.equation, r.power): r for r in errata_table()}
    differs = {key for key, r in rows.items() if r.status == "differs"}
    # derived in tests/test_power_balance.py; independent checks there
    assert differs == {("17", 6), ("19", 4)}
    # eqs 18 and 20 at kappa^6 hold for Bloch with square elements only (r = b/h = 2)
    assert rows[("18", 6)].reproduced_by == ("bloch r=2",)
    assert rows[("20", 6)].reproduced_by == ("bloch r=2",)
    assert all(r.status == "match" for key, r in rows.items() if key[0] in ("14", "15"))


def test_printed_eq13_leading_balance():
    notes = dict((b, (std, pr)) for b, std, pr in eq13_note())
    assert notes["A0"][1] == "-4"  # no root: the printed eq 13 has no A0 branch through 0
    assert "w" in notes["S0"][1]


def test_formats_render_every_row():
    rows = errata_table(equations=("18",))
    for fmt in ("text", "markdown", "latex"):
        out = format_table(rows, fmt)
        assert out.count("kappa") >= 2 or out.count("kappa\\^{}") >= 2
