"""Did a run reproduce the reference? A walk of two results with per-field rules.

Each report section may declare ``TOLERANCES``: a tuple of :class:`Rule`, matched in order
against the dotted path of every leaf of its stored ``result`` (list items as ``[]``, ``*``
as a wildcard, :func:`fnmatch.fnmatchcase`); the first rule that matches decides. A leaf that
no rule matches must be *identical* (strings, integers, booleans, and floats bit for bit), so
a section that declares nothing is held to the strictest standard. The kinds:

``exact``
    identical values (exact series, counts, labels).
``close``
    ``|new - ref| <= abs + rel * |ref|`` (floats from floating-point algorithms).
``within``
    the new value lies in the interval ``[lo, hi]`` read from two other fields of the
    *reference* (e.g. the spread of round-off-perturbed ring runs), widened on each side by
    ``widen`` times its width, and by at least ``abs``.
``timing``
    a wall time or a quantity fitted to wall times: listed as the ratio new/ref, never judged.
``unjudged``
    recorded for the reader, not compared (the ``why`` says why).
``machine``
    describes the machine that ran, not the physics (a peer program present or not, its
    version, status and messages, notes on the installation, paths): recorded, never
    compared, counted with the values not judged. A reproduction judges physics only, so
    a machine without an optional peer reproduces as well as one with it.

Missing or extra keys, lists of other lengths and ``null`` against a number are
disagreements unless the rule is ``timing``, ``unjudged`` or ``machine``.

What the machine lacked is said in the verdict instead: a section may define
``missing_peers(result) -> tuple[Peer, ...]`` (the peers its stored result shows were not
installed or failed), and :attr:`Verdict.peers` carries them into the verdict, one line
each, with the command that installs the peer.

>>> rules = (close("x", rel=1e-12), timing("seconds"))
>>> c = compare_results("demo", {"x": 1.0, "n": 3, "seconds": 2.0},
...                     {"x": 1.0 + 1e-15, "n": 3, "seconds": 3.0}, rules)
>>> c.agree, c.disagree, [round(t.ratio, 2) for t in c.timings]
(2, [], [1.5])
>>> compare_results("demo", {"n": 3}, {"n": 4}, rules).disagree[0].path
'n'
"""
from __future__ import annotations

import fnmatch
import functools
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

__all__ = [
    "Rule", "exact", "close", "within", "timing", "unjudged", "machine",
    "Difference", "Timing", "SectionComparison", "Verdict", "Peer",
    "compare_results", "compare_envelopes", "rules_of", "missing_peers",
]


@dataclass(frozen=True)
class Rule:
    """How the leaves whose path matches ``pattern`` are compared (see the module docstring)."""

    pattern: str
    kind: str
    rel: float = 0.0
    abs: float = 0.0
    lo: str | None = None
    hi: str | None = None
    widen: float = 0.0
    why: str = ""

    def matches(self, path: str) -> bool:
        return self.matches_generic(_generic(path))

    def matches_generic(self, generic: str) -> bool:
        """:meth:`matches` for a path whose list indices are already ``[]``."""
        return _compiled(self.pattern).match(generic) is not None

    def describe(self) -> str:
        if self.kind == "close":
            return f"|new - ref| <= {self.abs:g} + {self.rel:g} |ref|"
        if self.kind == "within":
            return (f"within reference [{self.lo}, {self.hi}] widened by {self.widen:g} x its "
                    f"width (at least {self.abs:g})")
        if self.kind == "machine":
            return "machine (not judged)"
        return self.kind


def exact(pattern: str, why: str = "") -> Rule:
    """Identical values."""
    return Rule(pattern, "exact", why=why)


def close(pattern: str, *, rel: float = 0.0, abs: float = 0.0, why: str = "") -> Rule:
    """``|new - ref| <= abs + rel * |ref|``."""
    if rel < 0 or abs < 0 or (rel == 0 and abs == 0):
        raise ValueError("close() needs rel >= 0, abs >= 0, not both zero")
    return Rule(pattern, "close", rel=rel, abs=abs, why=why)


def within(pattern: str, lo: str, hi: str, *, widen: float = 1.0, abs: float = 0.0,
           why: str = "") -> Rule:
    """The new value in the reference's ``[lo, hi]`` (paths), widened by ``widen`` x width.

    On list items, each ``[]`` of ``lo`` and ``hi`` takes the index of the matched leaf's
    list at that place: ``within("rows[].x", "rows[].x_min", "rows[].x_max")`` judges
    ``rows[3].x`` by the reference's ``rows[3]`` spread.
    """
    return Rule(pattern, "within", lo=lo, hi=hi, widen=widen, abs=abs, why=why)


def timing(pattern: str, why: str = "") -> Rule:
    """A wall time (or a number fitted to wall times): ratio listed, not judged."""
    return Rule(pattern, "timing", why=why)


def unjudged(pattern: str, why: str) -> Rule:
    """Not compared; ``why`` says why."""
    return Rule(pattern, "unjudged", why=why)


def machine(pattern: str, what: str) -> Rule:
    """A field that describes the machine, not the physics (``what`` says which): not judged.

    >>> machine("maxima", "version of Maxima").describe()
    'machine (not judged)'
    """
    if not what:
        raise ValueError("machine() needs a description of what the field records")
    return Rule(pattern, "machine", why=f"describes the machine: {what}")


@dataclass(frozen=True)
class Peer:
    """An optional program a section runs beside ours that this machine lacked, or that failed.

    >>> Peer("Maxima", "not installed", "race not run", "apt-get install maxima maxima-share").line()
    'Maxima not installed: race not run; apt-get install maxima maxima-share'
    """

    name: str
    problem: str
    consequence: str
    remedy: str

    def line(self) -> str:
        return f"{self.name} {self.problem}: {self.consequence}; {self.remedy}"


@dataclass(frozen=True)
class Difference:
    """A leaf that does not agree: where, the two values, and the rule it broke."""

    section: str
    path: str
    reference: object
    new: object
    rule: str

    def line(self) -> str:
        return f"{self.section}: {self.path}: reference {self.reference!r}, new {self.new!r} ({self.rule})"


@dataclass(frozen=True)
class Timing:
    """A timing leaf: reference and new value and their ratio (new / reference)."""

    section: str
    path: str
    reference: float | None
    new: float | None

    @property
    def ratio(self) -> float | None:
        if not _number(self.reference) or not _number(self.new) or self.reference == 0:
            return None
        return self.new / self.reference


@dataclass(frozen=True)
class SectionComparison:
    """The comparison of one section: counts, disagreements, timings, or why it was skipped."""

    section: str
    agree: int = 0
    disagree: list[Difference] = field(default_factory=list)
    timings: list[Timing] = field(default_factory=list)
    unjudged: int = 0
    skipped: str | None = None
    rules: tuple[Rule, ...] = ()


@dataclass(frozen=True)
class Verdict:
    """The comparison of a run with the reference, section by section."""

    reference: str
    sections: list[SectionComparison]
    peers: tuple[Peer, ...] = ()

    @property
    def agree(self) -> int:
        return sum(s.agree for s in self.sections)

    @property
    def disagree(self) -> list[Difference]:
        return [d for s in self.sections for d in s.disagree]

    @property
    def timings(self) -> list[Timing]:
        return [t for s in self.sections for t in s.timings]

    @property
    def compared(self) -> list[str]:
        return [s.section for s in self.sections if s.skipped is None]

    @property
    def reproduced(self) -> bool:
        """True unless a physics figure disagrees (timings are never judged)."""
        return not self.disagree

    def line(self) -> str:
        """The one-line verdict, e.g. ``reproduced: 9120 figures agree with reports/ ...``."""
        if not self.compared:
            why = "; ".join(f"{s.section}: {s.skipped}" for s in self.sections) or "no sections"
            return f"not compared with {self.reference}: {why}"
        ratios = [t.ratio for t in self.timings if t.ratio is not None]
        if ratios:
            lo, hi = min(ratios), max(ratios)
            times = (f"{len(ratios)} timings differ by x{lo:.2g} to x{hi:.2g} "
                     f"(new/reference, not judged)")
        else:
            times = "no timings"
        where = f"{self.reference} ({', '.join(self.compared)})"
        skipped = [s.section for s in self.sections if s.skipped is not None]
        tail = f"; not compared: {', '.join(skipped)}" if skipped else ""
        unjudged_count = sum(s.unjudged for s in self.sections)
        if unjudged_count:
            times += f", {unjudged_count} values not judged (comparison.md says why)"
        if self.peers:
            names = ", ".join(dict.fromkeys(p.name for p in self.peers))
            tail += f"; peers not run here: {names} (below)"
        if self.reproduced:
            return f"reproduced: {self.agree} figures agree with {where}, {times}{tail}"
        d = self.disagree
        return (f"NOT reproduced: {len(d)} of {self.agree + len(d)} figures disagree with "
                f"{where} (first: {d[0].section} {d[0].path}), {times}{tail}")

    def lines(self) -> list[str]:
        """The verdict line, then one line per peer this machine lacked (with its remedy)."""
        return [self.line(), *(p.line() for p in self.peers)]

    def markdown(self) -> str:
        """Every disagreement, every timing ratio and every skipped section, as Markdown."""
        lines = ["# Comparison with the reference", "", self.line(), ""]
        if self.peers:
            lines += ["Peers not run on this machine (their fields describe the machine and "
                      "are not judged):", "", *(f"- {p.line()}" for p in self.peers), ""]
        for s in self.sections:
            lines += [f"## {s.section}", ""]
            if s.skipped is not None:
                lines += [f"Not compared: {s.skipped}.", ""]
                continue
            lines.append(f"{s.agree} figures agree, {len(s.disagree)} disagree, "
                         f"{s.unjudged} not judged.")
            lines.append("")
            if s.rules:
                lines += ["| rule | fields | why |", "|---|---|---|"]
                lines += [f"| {_cell(r.describe())} | `{r.pattern}` | {_cell(r.why)} |"
                          for r in s.rules]
                lines.append("")
            if s.disagree:
                lines += ["| field | reference | new | rule |", "|---|---|---|---|"]
                lines += [f"| {d.path} | {_cell(repr(d.reference))} | {_cell(repr(d.new))} | "
                          f"{_cell(d.rule)} |" for d in s.disagree[:200]]
                if len(s.disagree) > 200:
                    lines.append(f"| ... {len(s.disagree) - 200} more | | | |")
                lines.append("")
            if s.timings:
                lines += ["| timing | reference | new | new / reference |", "|---|---|---|---|"]
                lines += [f"| {t.path} | {_fmt(t.reference)} | {_fmt(t.new)} | "
                          f"{'-' if t.ratio is None else f'{t.ratio:.3g}'} |" for t in s.timings]
                lines.append("")
        return "\n".join(lines) + "\n"


def _cell(text: str) -> str:
    """Text safe in a Markdown table cell."""
    return text.replace("|", "\\|").replace("\n", " ")


def _fmt(x) -> str:
    return "-" if x is None else f"{x:.4g}" if isinstance(x, float) else str(x)


def _number(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


_INDEX = re.compile(r"\[[^\]]*\]")


def _generic(path: str) -> str:
    """``a[3].b`` -> ``a[].b``: rules name list items without their index."""
    return _INDEX.sub("[]", path)


@functools.lru_cache(maxsize=1024)
def _compiled(pattern: str) -> re.Pattern:
    # "[]" in a pattern is the literal list marker of _generic, not an fnmatch character
    # set ("curves[].error[]" would read "].error[" as one); only "*" and "?" are wild
    literal = pattern.replace("[", "\0").replace("]", "[]]").replace("\0", "[[]")
    return re.compile(fnmatch.translate(literal), re.DOTALL)


def _get(data, path: str):
    node = data
    for part in path.replace("]", "").replace("[", ".").split("."):
        node = node[int(part)] if isinstance(node, list) else node[part]
    return node


def _leaves(data, prefix: str = ""):
    if isinstance(data, Mapping):
        for key, value in data.items():
            yield from _leaves(value, f"{prefix}.{key}" if prefix else str(key))
    elif isinstance(data, list):
        for i, value in enumerate(data):
            yield from _leaves(value, f"{prefix}[{i}]")
    else:
        yield prefix, data


_EXACT = Rule("*", "exact")


def _rule(rules: Sequence[Rule], path: str, seen: dict | None = None) -> Rule:
    """The first rule matching ``path`` (identical values if none); ``seen`` memoizes the
    answer per generic path (the leaves of a list share it)."""
    generic = _generic(path)
    if seen is not None and generic in seen:
        return seen[generic]
    rule = next((r for r in rules if r.matches_generic(generic)), _EXACT)
    if seen is not None:
        seen[generic] = rule
    return rule


def compare_results(section: str, reference, new, rules: Sequence[Rule] = ()) -> SectionComparison:
    """Compare two stored results (plain JSON data) leaf by leaf under ``rules``."""
    ref_leaves = dict(_leaves(reference))
    new_leaves = dict(_leaves(new))
    agree, unjudged_count, disagree, timings, seen = 0, 0, [], [], {}
    for path in list(ref_leaves) + [p for p in new_leaves if p not in ref_leaves]:
        rule = _rule(rules, path, seen)
        a = ref_leaves.get(path, _MISSING)
        b = new_leaves.get(path, _MISSING)
        if rule.kind in ("unjudged", "machine"):
            unjudged_count += 1
            continue
        if rule.kind == "timing":
            timings.append(Timing(section, path, a if _number(a) else None,
                                  b if _number(b) else None))
            continue
        if a is _MISSING or b is _MISSING:
            disagree.append(Difference(section, path, None if a is _MISSING else a,
                                       None if b is _MISSING else b,
                                       "missing in the " + ("reference" if a is _MISSING
                                                            else "new run")))
            continue
        if _agrees(rule, a, b, reference, path):
            agree += 1
        else:
            disagree.append(Difference(section, path, a, b, rule.describe()))
    return SectionComparison(section, agree, disagree, timings, unjudged_count,
                             rules=tuple(rules))


_MISSING = object()


def _bind(template: str, path: str) -> str:
    """``template`` with each ``[]`` replaced by the next list index of ``path``."""
    indices = iter(re.findall(r"\[(\d+)\]", path))
    return re.sub(r"\[\]", lambda m: f"[{next(indices, '')}]", template)


def _agrees(rule: Rule, a, b, reference, path: str = "") -> bool:
    if rule.kind == "exact" or not (_number(a) and _number(b)):
        return type(a) is type(b) and a == b or (_number(a) and _number(b) and a == b)
    if rule.kind == "close":
        return abs(b - a) <= rule.abs + rule.rel * abs(a)
    if rule.kind == "within":
        try:
            lo, hi = _get(reference, _bind(rule.lo, path)), _get(reference, _bind(rule.hi, path))
        except (KeyError, IndexError, ValueError, TypeError):  # a reference without the band
            return False
        if not (_number(lo) and _number(hi)):
            return False
        margin = max(rule.widen * (hi - lo), rule.abs)
        return lo - margin <= b <= hi + margin
    raise ValueError(f"unknown rule kind {rule.kind!r}")


def rules_of(name: str) -> tuple[Rule, ...]:
    """The ``TOLERANCES`` declared by report section ``name`` (empty: every leaf identical)."""
    from dispersion.report import section_module

    return tuple(getattr(section_module(name), "TOLERANCES", ()))


def missing_peers(name: str, result) -> tuple[Peer, ...]:
    """The peers the stored ``result`` of section ``name`` shows were not run (its
    ``missing_peers``; none if the section runs no peer)."""
    from dispersion.report import section_module

    find = getattr(section_module(name), "missing_peers", None)
    return tuple(find(result)) if callable(find) else ()


def compare_envelopes(name: str, reference: Mapping, new: Mapping,
                      rules: Sequence[Rule] | None = None) -> SectionComparison:
    """Compare two stored envelopes of section ``name``; skipped if their inputs differ.

    A result measured with other inputs (``--quick`` against the full reference) is not
    comparable: the section is reported as skipped with the reason, never as agreeing.
    """
    if reference.get("inputs") != new.get("inputs"):
        return SectionComparison(name, skipped=(
            f"measured with inputs {new.get('inputs')}, the reference with "
            f"{reference.get('inputs')}"))
    rules = rules_of(name) if rules is None else rules
    comparison = compare_results(name, reference["result"], new["result"], rules)
    seconds = Timing(name, "seconds (whole section)", reference.get("seconds"), new.get("seconds"))
    return SectionComparison(name, comparison.agree, comparison.disagree,
                             [seconds, *comparison.timings], comparison.unjudged,
                             rules=tuple(rules))


def compare_folders(reference: Path, new: Path, names: Sequence[str]) -> Verdict:
    """Compare ``new/<name>.json`` with ``reference/<name>.json`` for each section name."""
    from dispersion import results

    reference, new = Path(reference), Path(new)
    sections = []
    for name in names:
        ref_path, new_path = reference / f"{name}.json", new / f"{name}.json"
        if not ref_path.is_file():
            sections.append(SectionComparison(name, skipped=f"no {name}.json in the reference"))
        elif not new_path.is_file():
            sections.append(SectionComparison(name, skipped=f"no {name}.json in this run"))
        else:
            sections.append(compare_envelopes(name, results.load(ref_path),
                                              results.load(new_path)))
    peers = tuple(p for name in names if (new / f"{name}.json").is_file()
                  for p in missing_peers(name, results.load(new / f"{name}.json")["result"]))
    return Verdict(f"{reference.name}/", sections, peers)
