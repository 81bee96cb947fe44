"""Tests of dispersion/report/compare.py: the rules that decide whether a run reproduced.

Properties over random JSON-like results (hypothesis): a result always agrees with itself;
changing any one judged leaf beyond its tolerance is always reported (never a silent pass);
timings are never judged; a changed shape is a disagreement.
"""
from __future__ import annotations

import copy
import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.report import SECTIONS
from dispersion.report.compare import (Verdict, close, compare_envelopes, compare_results,
                                       timing, unjudged, within, _leaves)

LEAF = st.one_of(st.none(), st.booleans(), st.integers(-10**6, 10**6), st.text(max_size=8),
                 st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False))
KEY = st.text("abcdefgh_", min_size=1, max_size=6)
DATA = st.recursive(LEAF, lambda inner: st.one_of(st.lists(inner, max_size=4),
                                                  st.dictionaries(KEY, inner, max_size=4)),
                    max_leaves=30)
RULES = (close("*", rel=1e-9, abs=1e-12),)


@settings(max_examples=60, deadline=None)
@given(DATA)
def test_a_result_agrees_with_itself(data):
    for rules in ((), RULES):
        c = compare_results("s", data, copy.deepcopy(data), rules)
        assert c.disagree == [] and c.agree == len(list(_leaves(data)))


def _changed(value):
    if isinstance(value, bool):
        return not value
    if isinstance(value, (int, float)):
        return value + 1 + abs(value) * 1e-6  # far beyond rel 1e-9 and abs 1e-12
    if isinstance(value, str):
        return value + "x"
    return 0.5  # None -> a number


@settings(max_examples=60, deadline=None)
@given(DATA, st.data())
def test_any_changed_judged_leaf_is_reported(data, draw):
    leaves = [p for p, _ in _leaves(data)]
    if not leaves:
        return
    path = draw.draw(st.sampled_from(leaves))
    new = copy.deepcopy(data)
    node, parts = new, [p for p in path.replace("]", "").replace("[", ".").split(".") if p]
    if not isinstance(data, (dict, list)):
        new = _changed(data)
    else:
        for part in parts[:-1]:
            node = node[int(part)] if isinstance(node, list) else node[part]
        last = int(parts[-1]) if isinstance(node, list) else parts[-1]
        node[last] = _changed(node[last])
    for rules in ((), RULES):
        c = compare_results("s", data, new, rules)
        assert [d.path for d in c.disagree] == [path]
        assert not Verdict("ref/", [c]).reproduced


def test_rules_close_within_timing_unjudged():
    ref = {"x": 1.0, "lo": -10.0, "hi": -9.0, "e": -9.5, "t": 2.0, "h": [1, 2, 3]}
    rules = (close("x", rel=1e-6), within("e", "lo", "hi", widen=1.0), timing("t"),
             unjudged("h[]", "chaotic"))
    ok = dict(ref, x=1.0 + 1e-7, e=-10.9, t=40.0, h=[9, 9])
    c = compare_results("s", ref, ok, rules)
    assert c.disagree == [] and [t.ratio for t in c.timings] == [20.0] and c.unjudged == 3
    bad = dict(ref, x=1.0 + 1e-5, e=-11.1)
    assert [d.path for d in compare_results("s", ref, bad, rules).disagree] == ["x", "e"]


def test_shape_changes_and_missing_keys_disagree():
    assert compare_results("s", {"a": [1, 2]}, {"a": [1, 2, 3]}).disagree[0].path == "a[2]"
    assert compare_results("s", {"a": 1, "b": 2}, {"a": 1}).disagree[0].rule.startswith("missing")
    assert compare_results("s", {"a": 1.0}, {"a": None}, (close("a", rel=1),)).disagree


def test_other_inputs_are_not_compared():
    env = {"inputs": {"quick": False}, "result": {"a": 1}, "seconds": 1.0}
    c = compare_envelopes("s", env, dict(env, inputs={"quick": True}), ())
    assert c.skipped and c.agree == 0
    v = Verdict("reports/", [c])
    assert v.reproduced and v.line().startswith("not compared with reports/")


@pytest.mark.parametrize("name", SECTIONS)
def test_each_section_declares_rules_that_compile(name):
    from dispersion.report.compare import rules_of

    for rule in rules_of(name):
        assert rule.kind in {"exact", "close", "within", "timing", "unjudged", "machine"}
        assert rule.kind not in ("unjudged", "machine") or rule.why  # a field not judged says why
        assert not (rule.kind == "close" and (math.isnan(rule.rel) or rule.rel >= 1e-3))


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(-10, 10), st.floats(0, 5)), min_size=1, max_size=5),
       st.data())
def test_within_on_list_items_judges_each_item_by_its_own_spread(bands, draw):
    # issue 23: a row of a list (a Signorini row) is judged by the reference's spread of
    # that same row; a value inside its own widened band agrees, one beyond it never does,
    # whatever the other rows' bands are
    ref = {"rows": [{"x": lo, "spread": {"min": lo, "max": lo + w}} for lo, w in bands]}
    rule = within("rows[].x", "rows[].spread.min", "rows[].spread.max", widen=1.0, abs=1e-6)
    i = draw.draw(st.integers(0, len(bands) - 1))
    lo, w = bands[i]
    margin = max(w, 1e-6)
    new = copy.deepcopy(ref)
    # inside by a hair: the band's width is (lo + w) - lo in floats, which may round below w
    inner = margin * (1 - 1e-9)
    new["rows"][i]["x"] = draw.draw(st.floats(lo - inner, lo + w + inner))
    assert compare_results("s", ref, new, [rule, close("*", abs=1e-300)]).disagree == []
    new["rows"][i]["x"] = lo + w + 1.5 * margin + 1e-9
    res = compare_results("s", ref, new, [rule, close("*", abs=1e-300)])
    assert [d.path for d in res.disagree] == [f"rows[{i}].x"]


def test_within_without_the_band_in_the_reference_disagrees():
    # an older reference without the spread: reported, not a crash and not a silent pass
    rule = within("rows[].x", "rows[].spread.min", "rows[].spread.max")
    res = compare_results("s", {"rows": [{"x": 1.0}]}, {"rows": [{"x": 1.0}]}, [rule])
    assert [d.path for d in res.disagree] == ["rows[0].x"]


def test_a_rule_with_two_list_markers_matches_its_fields():
    # fnmatch read "curves[].error[]" as a character set "].error[": the rule never matched and
    # its fields fell back to "exact" (found when round-off moved per_wavelength errors by 1e-16)
    from dispersion.report.compare import _rule

    rule = close("per_wavelength.curves[].error[]", rel=1e-6)
    assert rule.matches("per_wavelength.curves[0].error[12]")
    assert not rule.matches("per_wavelength.curves[0].kappa[12]")
    assert _rule([rule], "per_wavelength.curves[3].error[1]") is rule
    assert close("a[]", rel=1).matches("a[7]") and not close("a[]", rel=1).matches("a")


def test_machine_fields_are_never_judged_and_peers_reach_the_verdict():
    from dispersion.report.compare import Peer, machine

    ref = {"x": 1.0, "peer": {"version": "5.46", "status": "ok"}, "notes": ["a", "b"]}
    new = {"x": 1.0, "peer": {"version": None}, "notes": ["Peer not found", "a", "b", "c"]}
    rules = (machine("peer.*", "the peer's run"), machine("notes[]", "notes on the machine"))
    c = compare_results("s", ref, new, rules)
    assert c.disagree == [] and c.agree == 1 and c.unjudged == 6  # peer.version, .status, notes[0..3]
    assert compare_results("s", ref, dict(new, x=2.0), rules).disagree[0].path == "x"
    peer = Peer("Peer", "not installed", "race not run", "apt-get install peer")
    v = Verdict("reports/", [c], (peer,))
    assert v.reproduced and v.line().endswith("; peers not run here: Peer (below)")
    assert v.lines()[1:] == ["Peer not installed: race not run; apt-get install peer"]
    assert "- Peer not installed: race not run; apt-get install peer" in v.markdown()
    with pytest.raises(ValueError):
        machine("x", "")
