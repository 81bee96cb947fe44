"""The exact plate: the Rayleigh-Lamb equation in its forms, its series, the traced branches, their
velocities and mode shapes, the frequency calculator and SH modes. The calculator asks a plate
model (``plate_model``: the protocol) for what it needs; the isotropic plate
(``isotropic_plate``) is the first member, the layered and anisotropic plate (``layered/``,
with its exact relation, its model and every mode of it found and certified) the second.

Layers and the map of moved modules: ARCHITECTURE.md.
"""
