"""The exact plate: the Rayleigh-Lamb equation in its forms, its series, the traced branches, their
velocities and mode shapes, the frequency calculator and SH modes.

Layers and the map of moved modules: ARCHITECTURE.md.
"""
