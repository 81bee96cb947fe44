"""The lattice: the periodic patch's pencil, its characteristic polynomial, certified roots and
slopes, the discrete branches and their errors, the bar and the SEM bar, discrete mode shapes
and their pairing with the exact ones.

Layers and the map of moved modules: ARCHITECTURE.md.
"""
