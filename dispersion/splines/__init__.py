"""The B-spline bases: the basis functions, their exact Gram and mass integrals, the C0 Lagrange
(spectral element) and interpolatory bases, and the kinds of matrix they make.

Layers and the map of moved modules: ARCHITECTURE.md.
"""
