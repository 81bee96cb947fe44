"""A benchmark's page: its table printed, and with ``--out`` its JSON and Markdown written
into the report folder as one unit (:func:`dispersion.io.write_files`: all new or all old,
nothing else of the folder touched, a folder dispersion did not write refused).

Imported by the ``bench_*.py`` scripts (``benchmarks/`` is on ``sys.path`` when one runs).
"""
from __future__ import annotations


def publish(out, stem: str, json_text: str, markdown: str) -> None:
    """Print ``markdown``; with a folder ``out``, write ``<stem>.json`` and ``<stem>.md``."""
    print(markdown)
    if out:
        from dispersion.io import write_files

        write_files(out, {f"{stem}.json": json_text, f"{stem}.md": markdown}, option="--out")
