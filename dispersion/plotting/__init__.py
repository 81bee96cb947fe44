"""Plot functions (matplotlib). Each takes ``ax=None`` and returns the Axes it drew on.

Numerics never import this package; it imports matplotlib lazily.
"""
