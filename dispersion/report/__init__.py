"""Report sections for ``dispersion reproduce``.

Each module exposes ``report(out: pathlib.Path, quick: bool = False, executor=None) -> str``:
it writes its files (atomically) into ``out`` and returns a Markdown section for
``index.md`` that links them with relative paths.
"""
