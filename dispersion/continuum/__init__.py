"""The exact plate: the Rayleigh-Lamb equation in its forms, its series, the traced branches, their
velocities and mode shapes, the frequency calculator and SH modes (the isotropic plate); in
``layered/`` the layered and anisotropic plate, its exact relation and every mode of it found
and certified.

Layers and the map of moved modules: ARCHITECTURE.md.
"""
