"""Materials: elastic laws in three dimensions and solids (a stiffness with its density).

:mod:`dispersion.materials.stiffness` holds the 6x6 stiffness in Voigt notation (isotropic,
transversely isotropic, orthotropic or any, rotated about the plate's normal, with complex
moduli for damping); :mod:`dispersion.materials.solid` a stiffness with its density, name and
source, the value each layer of a plate is made of.
"""
