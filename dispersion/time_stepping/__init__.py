"""Time stepping: the Newmark members, the critical steps of the lattice, the proven bound on the
highest frequency, the fully discrete branches.

Layers and the map of moved modules: ARCHITECTURE.md.
"""
