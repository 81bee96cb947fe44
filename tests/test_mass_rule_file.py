"""Untrusted ``--mass-rule`` files (dispersion/mass_rules/mass_rule_file.py, issue 27 item 7):
read as claims files are, every bad file refused in one line that names it.

The corpus ``tests/data/mass_rule_corpus.txt`` (one case a line) and the file-level cases
below run through the API (:func:`read_rule_file`, and the rule applied to a space where
what it says depends on the space) and through ``dispersion timestep --mass-rule``: each
must be an :class:`InputError` / exit status 2 with exactly one line that names the file and
holds no escape or control character. The base rule of the corpus header is accepted, so
the corpus cannot pass by refusing everything. Every case also runs under a 20 s alarm
(a hang fails); the time of each is measured by ``benchmarks/bench_untrusted_files.py``.
"""
from __future__ import annotations

import os
import signal
from pathlib import Path

import pytest

from dispersion.cli import main
from dispersion.errors import InputError
from dispersion.mass_rules.mass_rule_file import MAX_FILE_BYTES, read_rule_file, rule_from_toml

CORPUS = Path(__file__).parent / "data" / "mass_rule_corpus.txt"
BASE = 'name = "corpus" ;; [weights] ;; "-1" = { "-2" = 0.5, "-3" = 0.5 }'


def corpus_cases() -> list[tuple[str, bytes]]:
    """``(label, bytes of the file)`` of every corpus line."""
    cases = []
    for number, line in enumerate(CORPUS.read_text(encoding="utf-8").splitlines(), 1):
        if not line.strip() or line.startswith("#"):
            continue
        if line.startswith("hex: "):
            data = bytes.fromhex(line[5:].replace(" ", ""))
        else:
            data = line.replace(" ;; ", "\n").encode("utf-8") + b"\n"
        cases.append((f"line {number}", data))
    return cases


def file_cases(root: Path) -> dict[str, Path]:
    """The cases that are files of a kind, not text: each a path under ``root``."""
    good = BASE.replace(" ;; ", "\n") + "\n"
    cases = {}
    (root / "zero.toml").symlink_to("/dev/zero")
    cases["a link to /dev/zero"] = root / "zero.toml"
    (root / "urandom.toml").symlink_to("/dev/urandom")
    cases["a link to /dev/urandom"] = root / "urandom.toml"
    os.mkfifo(root / "pipe.toml")
    cases["a named pipe nobody writes"] = root / "pipe.toml"
    (root / "folder.toml").mkdir()
    cases["a folder"] = root / "folder.toml"
    cases["a missing file"] = root / "missing.toml"
    (root / "dangling.toml").symlink_to(root / "nowhere.toml")
    cases["a dangling link"] = root / "dangling.toml"
    for name in ("rule.txt", "rule", "rule.toml.bak", "rule.TOM"):
        (root / name).write_text(good)
        cases[f"a valid rule named {name}"] = root / name
    (root / "big.toml").write_text(good + "#" * MAX_FILE_BYTES)
    cases["a file over the size limit"] = root / "big.toml"
    (root / "deep.toml").write_text("x = " + "[" * 100000 + "]" * 100000 + "\n")
    cases["100000 nested arrays"] = root / "deep.toml"
    (root / "deep2.toml").write_text("x = " + "[" * 900 + "]" * 900 + "\n")
    cases["900 nested arrays"] = root / "deep2.toml"
    (root / "digits.toml").write_text(good.replace("0.5,", "0.5, \"-4\" = " + "9" * 5000 + ","))
    cases["an integer of 5000 digits"] = root / "digits.toml"
    many = "\n".join(f'"{i}" = {{ "-1" = 1.0 }}' for i in range(65))
    (root / "many.toml").write_text(f'name = "many"\n[weights]\n{many}\n')
    cases["65 contact indices"] = root / "many.toml"
    (root / "esc\x1b[2J.toml").write_text("name = \n")
    cases["an escape sequence in the file name"] = root / "esc\x1b[2J.toml"
    return cases


class _Alarm:
    """Fail, not hang: a case that takes 20 s is an error (the bound is about a second)."""

    def __enter__(self):
        def fire(signum, frame):
            raise TimeoutError("case took more than 20 s")

        self.previous = signal.signal(signal.SIGALRM, fire)
        signal.alarm(20)

    def __exit__(self, *exc):
        signal.alarm(0)
        signal.signal(signal.SIGALRM, self.previous)


def _refused_by_the_api(path: Path) -> str:
    with _Alarm(), pytest.raises(InputError) as info:
        rule = read_rule_file(path)
        from dispersion.symbolic.plate import plate_patch

        plate_patch(2, 3, "bloch", 2, rule)  # what depends on the space
    return str(info.value)


def _refused_by_the_cli(path: Path, capsys) -> str:
    capsys.readouterr()
    with _Alarm():
        assert main(["timestep", "--p", "2", "--mass-rule", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    return err[0]


def _one_clean_line_naming(text: str, path: Path) -> None:
    from dispersion.untrusted import printable

    assert printable(path.name) in text, (text, path.name)
    assert all(ch == " " or ch.isprintable() for ch in text), repr(text)
    assert "\n" not in text


def test_the_corpus_is_large_and_its_base_rule_is_accepted(tmp_path):
    assert len(corpus_cases()) >= 100
    path = tmp_path / "base.toml"
    path.write_text(BASE.replace(" ;; ", "\n") + "\n")
    rule = read_rule_file(path)
    assert rule.name == "corpus" and rule_from_toml(path).name == "corpus"
    from dispersion.symbolic.plate import plate_patch

    plate_patch(2, 3, "bloch", 2, rule)


@pytest.mark.parametrize("label, data", corpus_cases(), ids=[c[0] for c in corpus_cases()])
def test_every_corpus_case_is_refused_in_one_line_naming_the_file(tmp_path, capsys, label, data):
    path = tmp_path / "rule.toml"
    path.write_bytes(data)
    _one_clean_line_naming(_refused_by_the_api(path), path)
    _one_clean_line_naming(_refused_by_the_cli(path, capsys), path)


def test_every_file_level_case_is_refused_in_one_line_naming_the_file(tmp_path, capsys):
    cases = file_cases(tmp_path)
    assert len(cases) == 16
    for label, path in cases.items():
        _one_clean_line_naming(_refused_by_the_api(path), path)
        _one_clean_line_naming(_refused_by_the_cli(path, capsys), path)


def test_toml_text_and_paths_are_told_apart(tmp_path):
    with pytest.raises(InputError, match="must end in .toml"):
        rule_from_toml("my_rule.txt")  # a path, never parsed as TOML text
    with pytest.raises(InputError, match="<string>: malformed TOML"):
        rule_from_toml('name = "x" ;; oops')
    assert rule_from_toml(BASE.replace(" ;; ", "\n")).name == "corpus"
