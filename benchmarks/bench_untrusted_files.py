"""Time and memory to refuse every untrusted TOML file of the corpora.

The promises timed (issues 27 and 34, finding 2): each refusal in under 2 s in one line naming
the file; the hostile shapes in under a second, at bounded memory, and never by the parser.

Run:  python benchmarks/bench_untrusted_files.py [--previous REF] [--timeout S]

Two parts.

1. ``tests/data/mass_rule_corpus.txt`` and the file-level cases of
   ``tests/test_mass_rule_file.py`` (a link to /dev/zero, a pipe, 100000 nested arrays, a file
   over the size limit, ...), timed in this process through ``dispersion timestep
   --mass-rule FILE`` (the first call's imports excluded by a warm-up).
2. The hostile corpus of ``tests/test_untrusted_bounds.py`` (dotted keys 30,000 parts deep in
   a 64 KiB rule file and 500,000 in a 1 MiB claims file, deep table headers, arrays and
   inline tables, keys as long as the file, too many keys), each case in a fresh process
   through the command line (``timestep --mass-rule`` for rule files, ``verify`` for claims
   files): wall seconds of the refusal and the growth of the process's peak resident memory
   during it (``ru_maxrss`` after minus before, imports warmed up), and, here, the peak of
   Python's allocations (``tracemalloc``). With ``--previous REF`` the issue's cases run the
   same way on the tree of ``REF`` (default: the merge base with main, HEAD~1 on main) in the same run, each
   under ``--timeout`` seconds (default 60) and a 4 GiB address-space limit, so a case that
   does not finish is reported as such, never timed.

The machine is shared: the lead re-times it on a quiet one.
"""
from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from test_mass_rule_file import corpus_cases, file_cases  # noqa: E402  (the same cases)
from test_untrusted_bounds import hostile_cases  # noqa: E402

from dispersion.cli import main  # noqa: E402

#: The issue's cases (raced against the previous commit): label prefixes per kind.
ISSUE = ("dotted key x.y.y", "table header [a.a.a", "nested arrays", "nested inline tables")

#: One refusal in a fresh process: warm the imports, then refuse the file, report as JSON.
_RUNNER = r"""
import contextlib, io, json, resource, sys, time
spec = json.loads(sys.stdin.read())
sys.path.insert(0, spec["tree"])
from dispersion.cli import main
from previous_commit import previous_commit  # noqa: E402  (benchmarks/ is on sys.path)


def run(argv):
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        status = main(argv)
    return status, err.getvalue().strip()
run(spec["warm"])
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
t0 = time.perf_counter()
status, line = run(spec["argv"])
seconds = time.perf_counter() - t0
after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(json.dumps({"status": status, "seconds": seconds, "line": line[:160],
                  "rss_growth_mib": (after - before) / 1024}))
"""


def _argv(kind: str, path: Path) -> list[str]:
    return (["timestep", "--p", "2", "--mass-rule", str(path)] if kind == "rule"
            else ["verify", str(path)])


def _child(tree: Path, kind: str, path: Path, warm: Path, timeout: float) -> dict:
    """One refusal in a fresh process of ``tree``'s code (see the module doc)."""
    def limit():  # a runaway parser must not take the shared machine's memory
        resource.setrlimit(resource.RLIMIT_AS, (4 * 2**30, 4 * 2**30))

    spec = {"tree": str(tree), "argv": _argv(kind, path), "warm": _argv(kind, warm)}
    try:
        done = subprocess.run([sys.executable, "-c", _RUNNER], input=json.dumps(spec),
                              capture_output=True, text=True, timeout=timeout,
                              preexec_fn=limit, cwd=path.parent,
                              env={**os.environ, "PYTHONDONTWRITEBYTECODE": "1"})
    except subprocess.TimeoutExpired:
        return {"not_finished": f"still running after {timeout:g} s (killed)"}
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or ["?"])[-1]
        return {"not_finished": f"the process failed: {last[:120]}"}
    return json.loads(done.stdout)


def _traced(kind: str, path: Path) -> float:
    """Peak of Python's allocations (MiB) while this process refuses ``path``."""
    with contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
        tracemalloc.start()
        try:
            main(_argv(kind, path))
            return tracemalloc.get_traced_memory()[1] / 2**20
        finally:
            tracemalloc.stop()


def _refuse(path: Path) -> tuple[int, float, str]:
    err = io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        status = main(["timestep", "--p", "2", "--mass-rule", str(path)])
    return status, time.perf_counter() - t0, err.getvalue().strip()


def corpus() -> None:
    """Part 1 (module doc)."""
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
    print(f"## Rule-file corpus\n\n{len(refused)} of {len(rows)} cases refused in one line "
          "(exit 2)")
    for label, status, seconds, line in sorted(rows, key=lambda r: -r[2])[:5]:
        print(f"{seconds:7.3f} s  {label}: {line[:100]}")
    print(f"slowest: {max(r[2] for r in rows):.3f} s\n")


def hostile(previous: str | None, timeout: float) -> None:
    """Part 2 (module doc)."""
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        tree = None
        if previous is not None:
            tree = root / "previous"
            subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree),
                            previous], check=True, capture_output=True)
        try:
            rows = []
            for kind in ("rule", "claims"):
                warm = root / f"warm-{kind}.toml"
                warm.write_text("name =\n")
                for i, (label, text, limit) in enumerate(hostile_cases(kind)):
                    path = root / f"{kind}{i}.toml"
                    path.write_text(text, encoding="utf-8")
                    ours = _child(ROOT, kind, path, warm, timeout)
                    ours["traced_mib"] = _traced(kind, path)
                    prev = (_child(tree, kind, path, warm, timeout)
                            if tree is not None and label.startswith(ISSUE) else None)
                    rows.append((kind, label, len(text.encode()), ours, prev))
                    path.unlink()
        finally:
            if tree is not None:
                subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force",
                                str(tree)], capture_output=True)
    print("## Hostile TOML (issue 34 finding 2), each refusal in a fresh process\n")
    head = "| file | case | bytes | exit | seconds | peak RSS growth [MiB] | traced peak [MiB] |"
    if previous is not None:
        head += f" previous ({previous}) |"
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    for kind, label, size, ours, prev in rows:
        cells = [kind, label, str(size)]
        if "not_finished" in ours:
            cells += [ours["not_finished"], "", "", ""]
        else:
            cells += [str(ours["status"]), f"{ours['seconds']:.3f}",
                      f"{ours['rss_growth_mib']:.1f}", f"{ours['traced_mib']:.1f}"]
        if previous is not None:
            cells.append("" if prev is None else prev.get("not_finished") or
                         f"exit {prev['status']}, {prev['seconds']:.2f} s, "
                         f"+{prev['rss_growth_mib']:.0f} MiB")
        print("| " + " | ".join(cells) + " |")
    done = [r for r in rows if "not_finished" not in r[3]]
    slow = max(done, key=lambda r: r[3]["seconds"])
    big = max(done, key=lambda r: r[3]["rss_growth_mib"])
    refused = sum(r[3].get("status") == 2 and len(r[3]["line"].splitlines()) == 1 for r in rows)
    print(f"\n{refused} of {len(rows)} refused in one line (exit 2). Slowest refusal: "
          f"{slow[3]['seconds']:.3f} s ({slow[0]} file, {slow[1]}); largest peak RSS growth: "
          f"{big[3]['rss_growth_mib']:.1f} MiB ({big[0]} file, {big[1]}); largest traced "
          f"peak: {max(r[3]['traced_mib'] for r in done):.1f} MiB.")


def run() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--previous", nargs="?", const="", default=None,
                    help="also race the hostile cases on this git ref (default when given "
                         "without a value: the merge base with main, HEAD~1 on main)")
    ap.add_argument("--timeout", type=float, default=60.0,
                    help="seconds a previous run may take before it is killed (default 60)")
    args = ap.parse_args()
    previous = None if args.previous is None else previous_commit(args.previous or None)
    corpus()
    hostile(previous, args.timeout)


if __name__ == "__main__":
    run()
