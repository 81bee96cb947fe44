"""Helpers of ``benchmarks/bench_series.py`` (baselines that are not part of the package)."""
