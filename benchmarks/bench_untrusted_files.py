"""Time to refuse every untrusted ``--mass-rule`` file of the corpus (issue 27: each in under
2 s, one line naming the file).

Run:  python benchmarks/bench_untrusted_files.py

Reads ``tests/data/mass_rule_corpus.txt`` and the file-level cases of
``tests/test_mass_rule_file.py`` (a link to /dev/zero, a pipe, 100000 nested arrays, a file
over the size limit, ...), times ``dispersion timestep --mass-rule FILE`` in this process for
each (wall seconds, the first call's imports excluded by a warm-up) and prints the slowest
cases and the count refused. The machine is shared: the lead re-times it on a quiet one.
"""
from __future__ import annotations

import contextlib
import io
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from test_mass_rule_file import corpus_cases, file_cases  # noqa: E402  (the same cases)

from dispersion.cli import main  # noqa: E402


def _refuse(path: Path) -> tuple[int, float, str]:
    err = io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        status = main(["timestep", "--p", "2", "--mass-rule", str(path)])
    return status, time.perf_counter() - t0, err.getvalue().strip()


def run() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        warm = root / "warm.toml"
        warm.write_text("name =\n")
        _refuse(warm)
        rows = []
        for label, data in corpus_cases():
            path = root / f"{label.replace(' ', '_')}.toml"
            path.write_bytes(data)
            rows.append((label, *_refuse(path)))
        sub = root / "files"
        sub.mkdir()
        for label, path in file_cases(sub).items():
            rows.append((label, *_refuse(path)))
    refused = [r for r in rows if r[1] == 2 and len(r[3].splitlines()) == 1]
    print(f"{len(refused)} of {len(rows)} cases refused in one line (exit 2)")
    for label, status, seconds, line in sorted(rows, key=lambda r: -r[2])[:5]:
        print(f"{seconds:7.3f} s  {label}: {line[:100]}")
    print(f"slowest: {max(r[2] for r in rows):.3f} s")


if __name__ == "__main__":
    run()
