"""Untrusted TOML is bounded before it is parsed (issue 34 finding 2).

tomllib's cost grows with the square of a dotted key's depth: a 60 KB ``--mass-rule`` file
``x.y.y... = 1`` (30,000 parts) ran over a minute and reached 3.5 GiB, a 50,000-deep table
header was refused after 17.6 s. :func:`dispersion.untrusted.check_toml` measures the raw text
in one linear scan (size, depth of tables, arrays and inline tables, dotted-key depth, key
length, number of keys) before the parser sees it.

The hostile corpus :func:`hostile_cases` (the issue's cases and their relatives, each at the
size limit of its kind of file) must be refused with one :class:`InputError` that names the
limit, through the API and the command line, without the parser ever being called. The time
and memory of each refusal are measured by ``benchmarks/bench_untrusted_files.py``; no test
here asserts a time. The scan must also never refuse what it should not: on random valid TOML
(hypothesis) its depth is the parsed data's depth exactly.
"""
from __future__ import annotations

import json
import re

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

from dispersion.claims import parse_claims
from dispersion.claims.claims_file import MAX_FILE_BYTES as CLAIMS_BYTES
from dispersion.claims.claims_file import MAX_NESTING as CLAIMS_DEPTH
from dispersion.cli import main
from dispersion.errors import InputError
from dispersion.mass_rules.mass_rule_file import MAX_FILE_BYTES as RULE_BYTES
from dispersion.mass_rules.mass_rule_file import MAX_KEYS as RULE_KEYS
from dispersion.mass_rules.mass_rule_file import rule_from_toml
from dispersion.untrusted import MAX_KEY_CHARS, MAX_KEYS, check_toml, nesting_depth

#: What each refusal must name: the limit it met.
LIMITS = {"depth": "nested more than", "key": "a key of", "keys": "keys and table headers",
          "bytes": "more than the limit of"}


def _fit(unit: str, head: str, tail: str, budget: int, close: str = "") -> str:
    """``head + unit * k + close * k + tail`` with the largest k that fits in ``budget`` bytes."""
    k = (budget - len(head) - len(tail)) // (len(unit) + len(close))
    return head + unit * k + close * k + tail


def hostile_cases(kind: str) -> list[tuple[str, str, str]]:
    """``(label, text, limit)`` of the hostile corpus for ``kind`` ("rule" or "claims"), each
    text at most the file size limit of its kind (so only the shape can refuse it)."""
    budget = RULE_BYTES if kind == "rule" else CLAIMS_BYTES
    cases = [
        ("dotted key x.y.y... = 1 (the issue's)", _fit(".y", "x", " = 1\n", budget), "depth"),
        ("dotted key of quoted parts", _fit('."y"', '"x"', " = 1\n", budget), "depth"),
        ("dotted key with spaces", _fit(" . y", "x", " = 1\n", budget), "depth"),
        ("table header [a.a.a...]", _fit("a.", "[", "a]\n", budget), "depth"),
        ("array-of-tables header [[a.a...]]", _fit("a.", "[[", "a]]\n", budget), "depth"),
        ("table headers one part deeper each",
         "".join(f"[{'.'.join(['a'] * j)}]\n" for j in range(1, 400)), "depth"),
        ("nested arrays", _fit("[", "x = ", "\n", budget, "]"), "depth"),
        ("nested arrays, unclosed", _fit("[", "x = ", "\n", budget), "depth"),
        ("nested inline tables", _fit("{a = ", "x = ", "1\n", budget, "}"), "depth"),
        ("inline tables of dotted keys", _fit("a.", "x = {", "a = 1}\n", budget), "depth"),
        ("arrays of inline tables", _fit("[{a = ", "x = ", "1\n", budget, "}]"), "depth"),
        ("a bare key as long as the file", _fit("k", "", " = 1\n", budget), "key"),
        ("a quoted key as long as the file", _fit("k", '"', '" = 1\n', budget), "key"),
        ("a long key in a header", _fit("k", "[", "]\n", budget), "key"),
        ("many keys", "".join(f"k{i} = 1\n" for i in range(budget // 8))[:budget], "keys"),
        ("many table headers", "".join(f"[t{i}]\n" for i in range(budget // 7))[:budget], "keys"),
        ("many keys of one inline table",
         "x = {" + ", ".join(f"k{i} = 1" for i in range(budget // 10)) + "}\n", "keys"),
        ("one byte over the size", "#\n" * (budget // 2) + "#", "bytes"),
        ("multi-byte characters over the size", "#\n" + "\u00e9" * (budget // 2), "bytes"),
    ]
    out = []
    for label, text, limit in cases:
        if limit != "bytes":
            text = text[:budget]
            assert len(text.encode()) <= budget, label
        out.append((label, text, limit))
    return out


def _refused(call, text: str, limit: str) -> str:
    with pytest.raises(InputError) as info:
        call(text)
    message = str(info.value)
    assert "\n" not in message and len(message) < 400, message
    assert LIMITS[limit] in message, message
    return message


@pytest.fixture
def no_parser(monkeypatch):
    """The parser must not see a refused text: it is bounded first."""
    def must_not_parse(*args, **kwargs):
        raise AssertionError("tomllib parsed untrusted text before bounding it")

    monkeypatch.setattr(tomllib, "loads", must_not_parse)


def test_the_corpus_is_the_issues_and_fits_the_files():
    for kind, budget in (("rule", RULE_BYTES), ("claims", CLAIMS_BYTES)):
        cases = hostile_cases(kind)
        assert len(cases) >= 19
        issue = cases[0][1]
        assert issue.count(".") >= (30_000 if kind == "rule" else 500_000) - 1
        assert all(len(t.encode()) <= budget for _, t, lim in cases if lim != "bytes")


def test_every_hostile_rule_file_is_refused_before_parsing(no_parser):
    for label, text, limit in hostile_cases("rule"):
        message = _refused(rule_from_toml, text, limit)
        assert message.startswith("mass rule <string>"), (label, message)


def test_every_hostile_claims_file_is_refused_before_parsing(no_parser):
    for label, text, limit in hostile_cases("claims"):
        message = _refused(lambda t: parse_claims(t, "h.toml"), text, limit)
        assert message.startswith("h.toml"), (label, message)


def test_the_command_line_refuses_the_issues_files_in_one_line(tmp_path, capsys, no_parser):
    rule = tmp_path / "r.toml"
    rule.write_text(hostile_cases("rule")[0][1])
    claims = tmp_path / "c.toml"
    claims.write_text(hostile_cases("claims")[0][1])
    header = tmp_path / "h.toml"
    header.write_text("[" + "a." * 50_000 + "a]\n")
    for argv, name in ((["timestep", "--p", "2", "--mass-rule", str(rule)], "r.toml"),
                       (["verify", str(claims)], "c.toml"), (["verify", str(header)], "h.toml")):
        assert main(argv) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and name in err and "nested more than" in err, err


def test_limits_are_the_parsed_ones_at_their_ends():
    # at the limit accepted, one over refused: each limit as stated
    at = "[" + ".".join(["a"] * CLAIMS_DEPTH) + "]\n"
    check_toml(at, "f", CLAIMS_BYTES, CLAIMS_DEPTH)
    with pytest.raises(InputError, match="nested more than 6"):
        check_toml("[" + ".".join(["a"] * (CLAIMS_DEPTH + 1)) + "]\n", "f", CLAIMS_BYTES,
                   CLAIMS_DEPTH)
    check_toml("k" * MAX_KEY_CHARS + " = 1", "f", 10**6, 1)
    with pytest.raises(InputError, match=f"limit of {MAX_KEY_CHARS}"):
        check_toml("k" * (MAX_KEY_CHARS + 1) + " = 1", "f", 10**6, 1)
    keys = "".join(f"k{i} = 1\n" for i in range(RULE_KEYS))
    check_toml(keys, "f", 10**6, 1, max_keys=RULE_KEYS)
    with pytest.raises(InputError, match=f"more than {RULE_KEYS} keys"):
        check_toml(keys + "z = 1\n", "f", 10**6, 1, max_keys=RULE_KEYS)
    assert MAX_KEYS >= 10_000  # a claims file of a thousand claims


def test_strings_and_comments_are_text_to_the_scan():
    text = ('a = "[[[{{{ \\" ]]] #"  # [[[[\n'
            "b = '[[[[.a.b.c'\n"
            'c = """\n[[[[\n"""" \n'
            "d = '''\n{{{{\n'''\n"
            '"k.e.y" = [ # [[[[\n  "]", \'[\',\n]\n'
            "t = 1979-05-27 07:32:00Z\n")
    data = tomllib.loads(text)
    assert nesting_depth(data, 10) == 1
    check_toml(text, "f", 10**6, 1)


def test_the_files_the_toolkit_ships_pass_the_scan():
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    files = [*root.glob("examples/**/*.toml"), root / "dispersion" / "data" / "paper_claims.toml"]
    assert len(files) >= 5
    for path in files:
        text = path.read_text(encoding="utf-8")
        depth = nesting_depth(tomllib.loads(text), 100)
        check_toml(text, str(path), CLAIMS_BYTES, depth)


# ------------------------------------------------------------------ the scan's depth is exact

_KEY = st.one_of(st.from_regex(r"[A-Za-z0-9_-]{1,6}", fullmatch=True),
                 st.text(alphabet=st.characters(blacklist_categories=("Cs",)), min_size=0,
                         max_size=6))
_SCALAR = st.one_of(st.integers(-10**6, 10**6), st.booleans(),
                    st.floats(allow_nan=False, allow_infinity=False, width=32),
                    st.text(alphabet=st.characters(blacklist_categories=("Cs",)), max_size=12))
_VALUE = st.recursive(_SCALAR, lambda inner: st.one_of(
    st.lists(inner, max_size=3), st.dictionaries(_KEY, inner, max_size=3)), max_leaves=12)


def _key(k: str) -> str:
    return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else json.dumps(k, ensure_ascii=False)


def _string(s: str, style: int) -> str:
    if style == 1 and "'" not in s and not re.search(r"[\x00-\x1f\x7f]", s):
        return f"'{s}'"
    if style == 2 and "\\" not in s and not re.search(r"[\x00-\x09\x0b-\x1f\x7f\"]", s):
        return f'"""{s}"""'
    return json.dumps(s, ensure_ascii=False)


def _inline(v, draw) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return _string(v, draw(st.integers(0, 2)))
    if isinstance(v, list):
        gap = draw(st.sampled_from([" ", "\n  ", " # [ { \n "]))
        return "[" + gap + ("," + gap).join(_inline(x, draw) for x in v) + gap + "]"
    return "{" + ", ".join(f"{_key(k)} = {_inline(x, draw)}" for k, x in v.items()) + "}"


def _table(path: list[str], table: dict, draw, lines: list[str]) -> None:
    later = []
    for k, v in table.items():
        if isinstance(v, dict) and v and draw(st.booleans()):
            if draw(st.booleans()):
                later.append(("table", k, v))
                continue
            for k2, v2 in v.items():  # a dotted key for each entry
                lines.append(f"{_key(k)} . {_key(k2)} = {_inline(v2, draw)}")
            continue
        if isinstance(v, list) and v and all(isinstance(x, dict) for x in v) and draw(
                st.booleans()):
            later.append(("array", k, v))
            continue
        lines.append(f"{_key(k)} = {_inline(v, draw)}" + draw(st.sampled_from(["", " # [[x"])))
    for kind, k, v in later:
        head = ".".join(_key(p) for p in path + [k])
        if kind == "table":
            lines.append(f"[{head}]")
            _table(path + [k], v, draw, lines)
        else:
            for element in v:
                lines.append(f"[[{head}]]")
                _table(path + [k], element, draw, lines)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.dictionaries(_KEY, _VALUE, min_size=1, max_size=4), draw=st.data())
def test_the_scan_measures_the_depth_the_parser_builds(data, draw):
    lines: list[str] = []
    _table([], data, draw.draw, lines)
    text = "\n".join(lines) + "\n"
    try:
        parsed = tomllib.loads(text)
    except tomllib.TOMLDecodeError:  # a form the generator cannot write (e.g. "" headers)
        return
    depth = nesting_depth(parsed, 100)
    check_toml(text, "f", 10**7, depth)  # valid TOML within the limit: never refused
    with pytest.raises(InputError, match="nested more than"):
        check_toml(text, "f", 10**7, depth - 1)
